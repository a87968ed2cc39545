"""The wanderer (Turtlebot3Drive): turtlebot3_drive's decisions, its fixed weaknesses, 120 s
without a collision."""
import math

import pytest

from fake_tb3.turtlebot3_drive import (ANGULAR_SPEED, LINEAR_SPEED, Turtlebot3Drive,
                                      read_beams)
from fake_tb3.lidar import LDS_01, Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import load_world

INCREMENT = LDS_01.angle_increment


def scan(front=3.5, left=3.5, right=3.5, samples=360):
    ranges = [math.inf] * samples
    ranges[0], ranges[30], ranges[330] = front, left, right
    return ranges


def test_reads_beams_0_30_330_with_inf_as_range_max():
    assert read_beams(scan(1.0, 2.0, 0.5), 0.0, INCREMENT, 3.5) == (1.0, 2.0, 0.5)
    assert read_beams(scan(math.inf, math.nan, 0.3), 0.0, INCREMENT, 3.5) == (3.5, 0.0, 0.3)


def test_short_or_odd_scans_do_not_crash():
    assert read_beams([], 0.0, INCREMENT, 3.5) is None
    assert read_beams([1.0] * 31, 0.0, INCREMENT, 3.5) is None  # no beam at 330
    assert read_beams([1.0] * 10, 0.0, 0.0, 3.5) is None
    # A 180-beam scan from -pi to pi: the beams are found by angle.
    step = 2 * math.pi / 180
    ranges = [3.0] * 180
    ranges[90] = 0.4                      # angle 0
    ranges[90 + 15] = 0.5                 # +30 degrees
    ranges[90 - 15] = 0.55                # -30 degrees
    assert read_beams(ranges, -math.pi, step, 3.5) == (0.4, 0.5, 0.55)


def test_decisions():
    beams = lambda ranges: read_beams(ranges, 0.0, INCREMENT, 3.5)  # noqa: E731
    assert Turtlebot3Drive().command(None, 0.0) == (0.0, 0.0)  # no scan yet: no spinning
    assert Turtlebot3Drive().command(beams(scan()), 0.0) == (LINEAR_SPEED, 0.0)
    assert Turtlebot3Drive().command(beams(scan(front=0.69)), 0.0) == (0.0, -ANGULAR_SPEED)
    assert Turtlebot3Drive().command(beams(scan(left=0.59)), 0.0) == (0.0, -ANGULAR_SPEED)
    assert Turtlebot3Drive().command(beams(scan(right=0.59)), 0.0) == (0.0, ANGULAR_SPEED)
    assert Turtlebot3Drive().command(beams(scan(left=0.61, right=0.61)), 0.0) == (LINEAR_SPEED, 0.0)


def test_a_turn_lasts_30_degrees_across_the_yaw_wrap():
    wanderer = Turtlebot3Drive()
    blocked = read_beams(scan(right=0.3), 0.0, INCREMENT, 3.5)
    clear = read_beams(scan(), 0.0, INCREMENT, 3.5)
    start = math.pi - 0.1  # turning left crosses +pi -> -pi
    assert wanderer.command(blocked, start) == (0.0, ANGULAR_SPEED)
    assert wanderer.command(clear, start + math.radians(29) - 2 * math.pi) == (0.0, ANGULAR_SPEED)
    assert wanderer.command(clear, start + math.radians(30.5) - 2 * math.pi) == (LINEAR_SPEED, 0.0)


@pytest.mark.parametrize('model, x, y, yaw', [('burger', 0.5, 0.5, 1.0), ('waffle', 2.0, 1.0, 2.0)])
def test_wanders_120_s_in_turtlebot3_world_without_a_collision(model, x, y, yaw):
    # The ROS timing: scans at 5 Hz, a decision at each odom (30 Hz), physics at 100 Hz.
    robot = SimRobot('', get_model(model), x, y, yaw, Laser(seed=7))
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    wanderer, beams, travelled = Turtlebot3Drive(), None, 0.0
    for tick in range(1, 12001):
        if tick % 20 == 0:
            beams = read_beams(list(simulation.scan(robot)), 0.0, INCREMENT, 3.5)
        if tick % 3 == 0:
            robot.command = wanderer.command(beams, robot.yaw)
        before = robot.x, robot.y
        simulation.step(0.01)
        travelled += math.hypot(robot.x - before[0], robot.y - before[1])
    assert robot.collisions == 0
    assert travelled > 20.0
