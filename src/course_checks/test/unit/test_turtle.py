"""The turtle checks on poses made by turtlesim's own core (no ROS): driving is no jump, a teleport
is; circles within and beyond their tolerance."""
import math

import numpy

from course_checks import turtle
from turtlesim.msg import Pose
from turtlesim.world import TICK_SECONDS, World


class Log:
    def info(self, *args):
        pass

    warning = error = info


def heard(world, ticks, every=1, teleport_at=None):
    """(arrival time, Pose) of turtle1 over `ticks` ticks, one pose in `every` heard; a teleport
    2 m ahead before tick `teleport_at`."""
    samples = []
    for tick in range(ticks):
        if tick == teleport_at:
            pose = world.turtle('turtle1')
            world.teleport_absolute('turtle1', pose.x + 2.0, pose.y, pose.theta)
        world.command_velocity('turtle1', 1.0, 0.0, 0.5, tick * TICK_SECONDS)
        world.tick(tick * TICK_SECONDS)
        current = world.turtle('turtle1')
        if tick % every == 0:
            samples.append((tick * TICK_SECONDS, Pose(x=current.x, y=current.y, theta=current.theta,
                                                      linear_velocity=current.linear_velocity)))
    return samples


def new_world():
    return World(Log())   # turtle1 in the middle, as turtlesim starts


def test_driving_is_no_jump_even_with_poses_missed():
    assert turtle.jumps(heard(new_world(), 300)) == []
    assert turtle.jumps(heard(new_world(), 300, every=7)) == []


def test_a_teleport_is_a_jump_and_named():
    samples = heard(new_world(), 100, teleport_at=50)
    assert len(turtle.jumps(samples)) == 1
    recorder = type('Recorder', (), {'entries': lambda self: samples})()
    verdict = turtle.no_jumps(recorder, 'turtle1')
    assert not verdict.passed and 'turtle1 jumped 1 times without driving there' in verdict.reason


def test_on_a_faster_clock_a_turtle_drives_farther_between_two_poses_heard():
    # 0.46 m at 1 m/s between two poses heard 0.2 wall s apart: a jump in real time, not at 5x.
    samples = [(0.0, Pose(x=4.66, y=7.03, linear_velocity=1.0)), (0.2, Pose(x=4.54, y=6.58, linear_velocity=1.0))]
    assert len(turtle.jumps(samples)) == 1
    assert turtle.jumps(samples, real_time_factor=5) == []


def test_a_standing_turtle_that_moves_jumped():
    samples = [(0.0, Pose(x=1.0, y=1.0)), (0.016, Pose(x=1.01, y=1.0))]
    assert turtle.jumps(samples) == [((1.0, 1.0), (1.01, 1.0))]


def test_circle_within_and_beyond_its_tolerance():
    angles = numpy.linspace(0, 2 * math.pi, 400)
    points = numpy.column_stack([3 + numpy.cos(angles), 4 + numpy.sin(angles)])
    assert turtle.circle(points, (3, 4), 1.0, 0.02).passed
    wide = turtle.circle(points * 1.05 - (0.15, 0.2), (3, 4), 1.0, 0.02)
    assert not wide.passed and 'a circle of radius 1.050 m' in wide.reason


def test_drives_at_judges_the_speed_in_turtlesim_time_even_with_poses_missed():
    samples = heard(new_world(), 200, every=1)
    verdict = turtle.drives_at(samples, 1.0, 0.5, 0.02)
    assert verdict.passed and verdict.reason == '1.00 m/s turning 0.50 rad/s'
    # A busy machine that hears the poses late does not slow the turtle down.
    late = [(arrival * 3, pose) for arrival, pose in samples]
    assert turtle.drives_at(late, 1.0, 0.5, 0.02).passed
    assert not turtle.drives_at(samples, 2.0, 0.5, 0.1).passed
    assert turtle.drives_at(samples[:1], 1.0, 0.5, 0.1).reason == '1 poses heard'


def test_a_printed_position_is_the_pose_within_the_tolerance():
    pose = Pose(x=5.544445, y=7.0)
    assert turtle.printed_position([(1.0, 1.0), (5.54, 7.0)], pose, 0.011).passed
    off = turtle.printed_position([(5.58, 7.0)], pose, 0.011)
    assert not off.passed and off.reason == 'last printed x: 5.58, y: 7.00'
    assert turtle.printed_position([], pose, 0.011).reason == 'no line `x: ..., y: ...` printed'


def test_at_pose_on_x_y_and_theta():
    assert turtle.at_pose(Pose(x=1.0, y=1.0, theta=0.0), (1.0, 1.0, 0.0), 1e-5).passed
    turned = turtle.at_pose(Pose(x=1.0, y=1.0, theta=0.1), (1.0, 1.0, 0.0), 1e-5)
    assert not turned.passed and turned.reason == 'at (1.00, 1.00, 0.10)'
