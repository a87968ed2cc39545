"""The top-down picture's contents."""
import numpy as np
import pytest

from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.render import FLOOR, OBSTACLE, ROBOT_COLOURS, SCAN, render, save_picture
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import load_world


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
