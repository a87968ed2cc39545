"""The check that printed poses are poses turtlesim published, on poses made by turtlesim's own
core (no ROS): a recorder that missed poses must not fail a node that printed them all; made-up,
constant and stale poses must fail."""
import logging
import random

import numpy
import pytest

from course_checks import printed_poses
from turtlesim.world import TICK_SECONDS, World


def drive(commands, start=None):
    """The poses turtle1 publishes, as float32 (x, y, theta) rows, one per tick, driven by
    (ticks, linear.x, angular.z) one after the other; a spawn pose (x, y, theta) moves it first."""
    world = World(logging.getLogger('turtlesim'), rng=random.Random(0))
    now = 100.0
    if start:
        world.teleport_absolute('turtle1', *start)
    poses = []
    for ticks, linear, angular in commands:
        for _ in range(ticks):
            world.command_velocity('turtle1', linear, 0.0, angular, now)   # as a teleop does, again and again
            world.tick(now)
            now += TICK_SECONDS
            turtle = world.turtle('turtle1')
            poses.append((turtle.x, turtle.y, turtle.theta))
    return numpy.array(poses, dtype=numpy.float32).astype(float)


def as_printed(poses):
    """The poses as a node prints them with %f: text with 6 decimals."""
    return [tuple('%f' % value for value in pose) for pose in poses]


LISTENER = [(40, 0.0, 0.0), (120, 1.0, 0.5), (80, 0.0, 0.0)]   # at rest, driven as the grader does, stopped
CIRCLE = [(450, 1.0, 1.0)]                                      # a full turn and more of exercise 3
SQUARE_CORNER = [(60, 2.0, 0.0), (50, 0.0, 2.0), (60, 2.0, 0.0)]  # a side, a turn on the spot, a side


def problem_of(printed, heard):
    return printed_poses.problem(printed_poses.judge(printed, heard))


@pytest.mark.parametrize('commands', [LISTENER, CIRCLE, SQUARE_CORNER])
def test_every_pose_heard_passes(commands):
    poses = drive(commands)
    judgement = printed_poses.judge(as_printed(poses), poses)
    assert printed_poses.problem(judgement) == ''
    assert (judgement.on_path, judgement.between, judgement.unexplained) == (len(poses), 0, [])


@pytest.mark.parametrize('commands', [LISTENER, CIRCLE, SQUARE_CORNER])
@pytest.mark.parametrize('drop', ['every other', 'random 60 %', 'bursts of 25'])
def test_poses_the_recorder_missed_still_count(commands, drop):
    poses = drive(commands)
    rng = random.Random(1)
    keep = {'every other': lambda i: i % 2 == 0,
            'random 60 %': lambda i: rng.random() > 0.6,
            'bursts of 25': lambda i: (i // 25) % 2 == 0 or i % 25 == 24}[drop]
    heard = poses[[i for i in range(len(poses)) if keep(i) or i == len(poses) - 1]]
    judgement = printed_poses.judge(as_printed(poses), heard)
    assert printed_poses.problem(judgement) == ''
    assert judgement.between > 0.2 * len(poses)
    # Only where the velocities changed between two heard poses may a printed one be off the path.
    assert len(judgement.unexplained) <= 2 * len(commands) * 25


def test_the_arc_between_two_heard_poses_holds_the_poses_in_between():
    poses = drive([(181, 1.0, 1.0)], start=(3.0, 4.0, 2.5))   # crosses theta = pi
    path = printed_poses.Path(poses[::30])
    places = [path.place(pose) for pose in poses]
    assert places[45] == pytest.approx(1.5, abs=1e-4)
    assert all(place is not None for place in places)
    numpy.testing.assert_allclose(numpy.diff(places), numpy.diff(places)[0], atol=1e-3)   # evenly, in order
    assert path.place(poses[45] + (0.0, 0.002, 0.0)) is None      # 2 mm beside the arc
    assert path.place(poses[45] + (0.0, 0.0, 0.002)) is None      # the right spot, turned a little more


def test_made_up_poses_fail():
    poses = drive(CIRCLE)
    heard = poses[::2]
    for made_up in ([(x + 0.01, y, theta) for x, y, theta in poses],          # 1 cm off
                    [(y, x, theta) for x, y, theta in poses],                 # x and y swapped
                    [(x, y, numpy.degrees(theta)) for x, y, theta in poses],  # theta in degrees
                    numpy.random.default_rng(2).uniform(0, 11, (len(poses), 3))):
        judgement = printed_poses.judge(as_printed(made_up), heard)
        assert judgement.on_path < 0.1 * judgement.judged
        assert 'lie nowhere on the path turtlesim published' in printed_poses.problem(judgement)


def test_a_few_made_up_among_many_true_pass_and_more_fail():
    poses = drive(CIRCLE)
    printed = as_printed(poses)
    few = printed[:]
    for index in range(10, len(poses), 20):   # 5 %
        few[index] = ('1.000000', '2.000000', '0.000000')
    assert problem_of(few, poses) == ''
    many = printed[:]
    for index in range(10, len(poses), 5):    # 20 %
        many[index] = ('1.000000', '2.000000', '0.000000')
    assert problem_of(many, poses).startswith('88 of the 450 printed poses lie nowhere on the path')


def test_constant_pose_fails():
    poses = drive(LISTENER)
    judgement = printed_poses.judge(as_printed([poses[0]] * 100), poses)
    assert judgement.on_path == 100
    assert 'the printed pose does not follow the turtle' in printed_poses.problem(judgement)


def test_stale_poses_fail():
    poses = drive(CIRCLE)
    two_seconds = int(2 / TICK_SECONDS)
    assert 'steps of the turtle\'s path behind its last pose' in problem_of(as_printed(poses[:-two_seconds]), poses)
    # Printed once in a while only: the turtle moved on meanwhile.
    assert 'skipped 100 steps' in problem_of(as_printed(poses[::100]), poses)


def test_poses_printed_again_out_of_order_are_off_the_path():
    poses = drive(CIRCLE)
    printed = as_printed(poses[:200]) + as_printed(poses[100:110]) + as_printed(poses[200:])
    judgement = printed_poses.judge(printed, poses)
    assert len(judgement.unexplained) == 10 and printed_poses.problem(judgement) == ''


def test_what_was_printed_before_or_after_the_recording_is_left_out():
    poses = drive(CIRCLE)[:300]   # less than a turn: no pose is on the path twice
    judgement = printed_poses.judge(as_printed(poses), poses[40:290])
    assert (judgement.skipped, judgement.judged, judgement.unexplained) == (50, 250, [])
    # ... unless nothing printed is on the path: then all of it is judged.
    judgement = printed_poses.judge(as_printed(poses[:40]), poses[40:])
    assert (judgement.skipped, judgement.on_path) == (0, 0)
    assert 'lie nowhere on the path' in printed_poses.problem(judgement)


def test_nothing_printed_or_heard():
    poses = drive(LISTENER)
    assert problem_of([], poses) == 'no pose printed'
    assert problem_of(as_printed(poses), []) == 'no pose heard from turtlesim to compare with'
    # A turtle that never moved: its one pose, printed again and again, is right.
    assert problem_of(as_printed(poses[:30]), poses[:30]) == ''


def test_summary_names_the_counts():
    poses = drive(CIRCLE)
    judgement = printed_poses.judge(as_printed(poses), poses[::3])   # the last heard: poses[447]
    assert printed_poses.summary(judgement) == '448 printed poses, 448 on the path turtlesim published (298 ' \
        'between poses the recorder missed)'
    assert judgement.skipped == 2
