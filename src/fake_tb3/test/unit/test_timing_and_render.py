"""Periodic ticks on the simulated clock, and the top-down picture's contents."""
import math

import numpy as np
import pytest

from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.render import FLOOR, OBSTACLE, ROBOT_COLOURS, SCAN, render, save_picture
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.timing import Pacer, Periodic
from fake_tb3.world import load_world


def test_periodic_keeps_the_exact_rate():
    odom = Periodic(30.0)
    ticks = []
    while odom.next_ns <= 10 * 10 ** 9:
        ticks.append(odom.next_ns)
        odom.advance()
    assert len(ticks) == 300 and ticks[-1] == 10 * 10 ** 9
    assert set(np.diff(ticks)) == {33333333, 33333334}
    for bad in (0, -5, math.inf, 'fast'):
        with pytest.raises(ValueError, match='odom_rate must be a'):
            Periodic(bad, 'odom_rate')


def test_pacer_runs_simulated_time_at_the_factor_and_gives_up_catching_up():
    pacer = Pacer(10.0, start_wall=100.0)
    assert pacer.due(10 ** 9) == pytest.approx(100.1)  # 1 simulated second, 0.1 wall second
    pacer.reached(10 ** 9, now=100.3)  # 0.2 s late: catches up
    assert pacer.due(2 * 10 ** 9) == pytest.approx(100.2)
    pacer.reached(2 * 10 ** 9, now=101.0)  # 0.8 s late: carries on from here
    assert pacer.due(3 * 10 ** 9) == pytest.approx(101.1)
    assert Pacer(0.5, start_wall=0.0).due(10 ** 9) == pytest.approx(2.0)
    for bad in (0.0, -1.0, math.inf, math.nan):
        with pytest.raises(ValueError, match='real_time_factor must be a positive number'):
            Pacer(bad, start_wall=0.0)


def test_picture_shows_world_robot_trail_and_scan(tmp_path):
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser(noise_stddev=0.0))
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    robot.command = (0.2, 0.0)
    for _ in range(500):  # 1 m along y = -0.5
        simulation.step(0.01)
    simulation.scan(robot)
    path = tmp_path / 'top.png'
    save_picture(simulation, str(path))
    image = np.asarray(render(simulation))
    # 100 px per metre; the view starts 0.5 m left of the outer wall corner (-3.2995) and 0.5 m
    # above the top of the small prisms (2.7 + 0.8066 sin 60 = 3.3985).
    def pixel(x, y, around=0):
        row, column = int(round((3.3985 + 0.5 - y) * 100)), int(round((x + 3.2995 + 0.5) * 100))
        if around:
            return {tuple(p) for p in image[row - around:row + around + 1, column]}
        return image[row, column]
    assert tuple(pixel(0.0, 0.0)) == OBSTACLE          # the middle pillar
    assert tuple(pixel(3.5, 0.0)) == OBSTACLE          # the big prism
    assert tuple(pixel(-2.8, -2.9)) == FLOOR           # outside the ring
    assert tuple(pixel(-2.5, 0.0)) == FLOOR            # between wall and pillars
    assert ROBOT_COLOURS[0] in pixel(-1.5, -0.5, around=2)  # the trail
    assert ROBOT_COLOURS[0] not in pixel(-1.5, -0.4, around=2)
    red = np.all(image == SCAN, axis=2)
    assert red.sum() > 200
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


def test_a_snapshot_is_drawn_as_the_simulation_was_when_taken():
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser(noise_stddev=0.0))
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    simulation.command(robot, 0.2, 0.0)
    for _ in range(100):
        simulation.step(0.01)
    simulation.scan(robot)
    snapshot = simulation.snapshot()
    picture = np.asarray(render(snapshot))
    assert np.array_equal(picture, np.asarray(render(simulation)))
    for _ in range(100):  # the simulation goes on; the snapshot does not
        simulation.step(0.01)
    simulation.scan(robot)
    copied = snapshot.robots[0]
    assert copied.pose == pytest.approx((-1.8, -0.5, 0.0)) and robot.x == pytest.approx(-1.6)
    assert copied.trail[-1][0] < -1.79 and robot.trail[-1][0] > -1.61
    assert np.array_equal(np.asarray(render(snapshot)), picture)
