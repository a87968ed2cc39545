"""What the core does with velocity commands (refusal, clamp, timeout) and what its IMU reads."""
import math

import pytest

from fake_tb3.imu import GRAVITY, ImuSensor
from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import CommandError, SimRobot, Simulation
from fake_tb3.world import World


def simulation_of(model='burger', name='', **options):
    robot = SimRobot(name, get_model(model), laser=Laser(noise_stddev=0.0))
    return Simulation(World('empty'), [robot], **options), robot


def run(simulation, seconds, dt=0.01):
    for _ in range(int(round(seconds / dt))):
        simulation.step(dt)


@pytest.mark.parametrize('linear, angular', [(math.nan, 0.0), (0.1, math.inf),
                                             (-math.inf, math.nan)])
def test_a_non_finite_command_is_refused_and_the_last_one_holds(linear, angular):
    simulation, robot = simulation_of(name='tb3_0')
    simulation.command(robot, -0.5, 0.25)
    with pytest.raises(CommandError, match=r'^tb3_0: ignoring cmd_vel with a non-finite velocity '
                                           r'\(linear.x %s, angular.z %s\)$' % (linear, angular)):
        simulation.command(robot, linear, angular)
    assert robot.command == (-0.5, 0.25)


def test_clamp_speed_limits_to_the_model():
    simulation, waffle = simulation_of('waffle', clamp_speed=True)
    assert simulation.command(waffle, 1.0, -5.0) is None  # asked for: no warning
    assert waffle.command == (0.26, -1.82)
    simulation, burger = simulation_of()
    simulation.command(burger, 1.0, -5.0)
    assert burger.command == (1.0, -5.0)  # Gazebo has no clamp


def test_the_command_timeout_stops_a_silent_robot_and_a_new_command_restarts_it(recording_log):
    simulation, robot = simulation_of(name='tb3_1', command_timeout=0.5, log=recording_log)
    simulation.command(robot, 0.2, 0.0)
    run(simulation, 0.5)
    assert robot.velocity == (0.2, 0.0)
    run(simulation, 0.02)
    # Stopped at the first step that begins more than 0.5 s after the command.
    assert robot.velocity == (0.0, 0.0) and 0.1 - 1e-9 < robot.x < 0.1 + 0.2 * 0.01 + 1e-9
    assert simulation.log.lines == [('info', 'tb3_1: no cmd_vel for 0.50 s, stopping')]
    run(simulation, 2.0)
    assert len(simulation.log.lines) == 1  # said once
    simulation.command(robot, 0.0, 1.0)
    run(simulation, 0.3)
    assert robot.velocity == (0.0, 1.0)
    # Commands that keep coming keep it going.
    for _ in range(10):
        simulation.command(robot, 0.0, 1.0)
        run(simulation, 0.3)
    assert robot.velocity == (0.0, 1.0)


def test_no_timeout_by_default_as_in_gazebo():
    simulation, robot = simulation_of()
    simulation.command(robot, 0.1, 0.0)
    run(simulation, 30.0, dt=0.1)
    assert robot.velocity == (0.1, 0.0) and robot.x == pytest.approx(3.0)
    with pytest.raises(ValueError, match='command timeout must be a finite number >= 0'):
        simulation_of(command_timeout=-1.0)


def test_imu_reads_yaw_rate_acceleration_and_gravity():
    simulation, robot = simulation_of()
    imu = ImuSensor(1 / 30)
    assert imu.read(robot) == (0.0, 0.0, 0.0, 0.0, GRAVITY)
    simulation.command(robot, 0.2, 0.5)
    run(simulation, 0.1)
    reading = imu.read(robot)
    assert reading.yaw == pytest.approx(0.05)
    assert reading.angular_velocity == 0.5
    assert reading.acceleration_x == pytest.approx(0.2 * 30)  # 0 to 0.2 m/s in one period
    assert reading.acceleration_y == pytest.approx(0.1)  # centripetal: 0.2 m/s x 0.5 rad/s
    assert reading.acceleration_z == GRAVITY
    assert imu.read(robot).acceleration_x == 0.0  # steady speed
    with pytest.raises(ValueError, match='IMU period must be positive'):
        ImuSensor(0.0)
