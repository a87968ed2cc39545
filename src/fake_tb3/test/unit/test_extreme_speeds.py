"""Any finite command, however fast: limited to light speed with a warning, a bounded cost per
step, no tunnelling, every contact counted, a pose that stays finite and inside the world."""
import math

import numpy as np
import pytest

from fake_tb3 import simulation as simulation_module
from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SPEED_OF_LIGHT, SimRobot, Simulation
from fake_tb3.world import World, load_world

BURGER_CORNER = get_model('burger').body_corner_radius
EXTREME_COMMANDS = [(1e308, 0.0), (-1e308, 0.0), (0.0, 1e308), (0.0, -1e308), (0.0, 1e6),
                    (1e308, 1e308), (-1.7976931348623157e308, 1.7976931348623157e308),
                    (1e308, -1.0), (1.0, 1e308), (1e6, 1e-300), (5e-324, 1e-310),
                    (-2.2250738585072014e-308, 5e-324)]
# The inner outline of turtlebot3_world's hexagonal wall: corners on the x axis, apothem 2.54.
WALL_NORMALS = [math.radians(30 + 60 * k) for k in range(6)]


def inside_the_wall(x, y):
    return all(x * math.cos(a) + y * math.sin(a) <= 2.54 for a in WALL_NORMALS)


def burger(x=0.0, y=0.0, yaw=0.0):
    return SimRobot('', get_model('burger'), x, y, yaw, Laser(noise_stddev=0.0))


@pytest.fixture
def tested_poses(monkeypatch):
    """Counts the poses the simulation tests for overlap and the clearances it computes: the work
    of a step, independent of the machine's speed."""
    counts = {'poses': 0, 'clearances': 0}
    boxes_overlap, clearance = simulation_module.boxes_overlap, simulation_module.clearance

    def counting_overlap(poses, *args):
        counts['poses'] += np.size(poses[0])
        return boxes_overlap(poses, *args)

    def counting_clearance(*args):
        counts['clearances'] += 1
        return clearance(*args)

    monkeypatch.setattr(simulation_module, 'boxes_overlap', counting_overlap)
    monkeypatch.setattr(simulation_module, 'clearance', counting_clearance)
    return counts


@pytest.mark.parametrize('linear, angular', EXTREME_COMMANDS)
def test_a_command_faster_than_light_is_limited_on_its_path(linear, angular):
    robot = burger()
    simulation = Simulation(World('empty'), [robot])
    notice = simulation.command(robot, linear, angular)
    new_linear, new_angular = robot.command
    fastest = abs(new_linear) + abs(new_angular) * BURGER_CORNER
    if abs(linear) + abs(angular) * BURGER_CORNER > SPEED_OF_LIGHT:
        assert fastest == pytest.approx(SPEED_OF_LIGHT, rel=1e-12)
        assert 'faster than light' in notice and notice.startswith('robot: cmd_vel linear.x')
        # The same path: the ratio of the speeds (the radius of the arc) and their signs hold.
        if linear and angular:
            assert new_linear / new_angular == pytest.approx(linear / angular, rel=1e-12)
        assert (math.copysign(1, new_linear), math.copysign(1, new_angular)) == (
            math.copysign(1, linear), math.copysign(1, angular))
    else:
        assert notice is None and robot.command == (linear, angular)


@pytest.mark.parametrize('linear, angular', EXTREME_COMMANDS)
def test_extreme_commands_in_turtlebot3_world(linear, angular, tested_poses):
    robot = burger(-2.0, -0.5)
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    simulation.command(robot, linear, angular)
    most_poses = most_clearances = 0
    for _ in range(100):
        before = dict(tested_poses)
        simulation.step(0.01)
        most_poses = max(most_poses, tested_poses['poses'] - before['poses'])
        most_clearances = max(most_clearances, tested_poses['clearances'] - before['clearances'])
        assert all(map(math.isfinite, robot.pose)) and all(map(math.isfinite, robot.velocity))
        assert inside_the_wall(robot.x, robot.y) and not simulation.overlapping(robot)
    # Bounded work per step whatever the speed: at most one turn is tested pose by pose, and a
    # straight path only where it passes near an obstacle (the world is 6 m across).
    assert most_poses <= 4 * simulation_module.SUBSTEPS_PER_BATCH
    assert most_clearances <= 40
    assert robot.collisions <= 100
    # A normal command still works afterwards: backing off or turning moves the robot.
    moved = []
    for command in ((-0.1, 0.0), (0.1, 0.0), (0.0, 1.0), (0.0, -1.0)):
        start = robot.pose
        simulation.command(robot, *command)
        simulation.step(0.01)
        moved.append(robot.pose != start)
        if robot.velocity == command:
            break
    assert robot.velocity in ((-0.1, 0.0), (0.1, 0.0), (0.0, 1.0), (0.0, -1.0)), moved


def test_random_extreme_commands_in_turtlebot3_world():
    # Commands change every 0.1 s, as the rostest sends them, among the extremes, their mixes and
    # ordinary speeds; the robot ends wherever it was stopped.
    random = np.random.default_rng(5)
    choices = [value for command in EXTREME_COMMANDS for value in command] + [0.0, 0.3, -2.0]
    robot = burger(-2.0, -0.5)
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    for _ in range(100):
        simulation.command(robot, *random.choice(choices, 2))
        for _ in range(10):
            simulation.step(0.01)
            assert inside_the_wall(robot.x, robot.y)
        assert not simulation.overlapping(robot)
    assert robot.collisions > 10


def test_light_speed_in_an_empty_world_stays_finite_and_cheap(tested_poses):
    robot = burger()
    simulation = Simulation(World('empty'), [robot])
    simulation.command(robot, 1e300, 1.0)  # trajectory.launch linear:=1e300
    for _ in range(10000):
        simulation.step(0.01)
    assert robot.x == pytest.approx(SPEED_OF_LIGHT * 100.0, rel=1e-6)
    assert all(map(math.isfinite, robot.pose)) and robot.collisions == 0
    assert tested_poses['poses'] == 0


def test_a_fast_spin_next_to_a_pillar_stops_at_the_contact(tested_poses):
    # As test_motion's waffle: its back-right corner meets the pillar after turning 3.8244 rad.
    waffle = SimRobot('', get_model('waffle'), 0.0, 0.0, 0.0, Laser(noise_stddev=0.0))
    simulation = Simulation(World('pillar', [{'type': 'circle', 'center': [0.0, 0.30],
                                              'radius': 0.1}]), [waffle])
    simulation.command(waffle, 0.0, 1e308)
    simulation.step(0.01)
    assert waffle.collisions == 1
    assert 3.80 < waffle.yaw + 2 * math.pi <= 3.8245
    assert not simulation.overlapping(waffle)
    assert tested_poses['poses'] <= 2 * simulation_module.SUBSTEPS_PER_BATCH


def test_leaving_one_obstacle_and_hitting_another_in_one_step_counts_both(recording_log):
    # Two walls facing each other: faces at x = -1.0 and x = 2.0.
    walls = World('two walls', [{'type': 'box', 'center': [2.05, 0.0], 'size': [0.1, 4.0]},
                                {'type': 'box', 'center': [-1.05, 0.0], 'size': [0.1, 4.0]}])
    robot = burger()
    simulation = Simulation(walls, [robot], log=recording_log)
    for command, front_or_back, count in (((1e308, 0.0), 2.0 - 0.038, 1),
                                          ((-1e308, 0.0), -1.0 + 0.102, 2),
                                          ((1e308, 0.0), 2.0 - 0.038, 3)):
        simulation.command(robot, *command)
        began = simulation.step(0.01)
        assert began == [robot] and robot.collisions == count
        assert robot.x == pytest.approx(front_or_back, abs=1e-5)
        simulation.step(0.01)  # pushing on: the same contact
        assert robot.collisions == count
    warnings = [text for level, text in recording_log.lines if level == 'warning']
    assert len(warnings) == 3 and warnings[2].endswith('the body touches an obstacle (collision 3)')


def test_no_tunnelling_at_light_speed_through_a_thin_wall():
    wall = {'type': 'polygon', 'points': [[2.0, -1.0], [2.0, 1.0], [2.0001, 1.0], [2.0001, -1.0]]}
    for yaw in (0.0, 0.3, -0.4):
        robot = burger(yaw=yaw)
        simulation = Simulation(World('thin', [wall]), [robot])
        simulation.command(robot, 1e308, 0.0)
        simulation.step(0.01)
        assert robot.collisions == 1 and robot.x < 2.0 and not simulation.overlapping(robot)
