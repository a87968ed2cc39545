"""laser_data is judged on the scans fake_tb3 sent after it applied the grader's turn, by its own
record: a node that cut the turn off (a subscriber can be told through the ROS APIs that a publisher
is gone) leaves a robot standing still, whose seeded scans a stored printout could show."""
import random
import types

import pytest
from sensor_msgs.msg import LaserScan

from course_checks import laser
from course_grader import rubric
from course_grader.labs import common, move_turtlebot3

import fake_runs

BEAMS = [0, 90, 180, 270, 359]
GRADER = '/course_grader'


def scans(count):
    """(wall s sent, LaserScan): a scan every 0.02 wall s and 0.2 simulated s, each unlike the one
    before."""
    sent = []
    for i in range(count):
        message = LaserScan(ranges=[1.0 + i / 10 + beam / 1000 for beam in range(360)])
        message.header.stamp.secs, message.header.stamp.nsecs = divmod(i * 200000000, 1000000000)
        sent.append((i * 0.02, message))
    return sent


def printed(sent):
    """The node's output lines, each block read 1 ms after its scan was sent: (wall s read, line)."""
    lines = []
    for at, message in sent:
        block = ['=' * 10] + [line for label, beam in zip(laser.LABELS, BEAMS)
                              for line in (label, repr(message.ranges[beam]))]
        lines += [(at + 0.001, line) for line in block]
    return lines


class FakeRun(fake_runs.FakeRun):
    """What check_laser_data asks of its Run: the node's output, fake_tb3's record."""

    def __init__(self, session, simulators, script, **settings):
        self.node = types.SimpleNamespace(
            name=script, lines=[line for _, line in session.output], explain=lambda: [], ended=lambda: False,
            launch=types.SimpleNamespace(timed_lines=lambda: session.output))
        # The run's wait: whether it would end now, with all the node printed and fake_tb3 sent.
        self.deadline = types.SimpleNamespace(
            wait=lambda condition, gave_up=None: session.waited.append(condition()))
        self.watch = types.SimpleNamespace(scan_entries=lambda: session.sent,
                                           command_senders=lambda but=None: [],
                                           first_command_of=lambda node: session.turned if node == GRADER else None)
        self.marks = session.marks


@pytest.fixture
def grading(monkeypatch):
    session = types.SimpleNamespace(rubric=rubric.load('move_turtlebot3'), marks=[], waited=[])
    monkeypatch.setattr(move_turtlebot3, 'Run', FakeRun)
    session.turns = []   # the angular speed of each Twist the grader published
    monkeypatch.setattr(move_turtlebot3.rospy, 'Publisher', lambda *args, **kwargs: types.SimpleNamespace(
        publish=lambda message: session.turns.append(message.angular.z), unregister=lambda: None))
    monkeypatch.setattr(move_turtlebot3.rospy, 'get_name', lambda: GRADER)
    return session


def test_the_scans_after_the_turn_are_judged_and_the_moment_marked(grading):
    grading.sent = scans(20)
    grading.output, grading.turned = printed(grading.sent), 0.9
    verdict = move_turtlebot3.check_laser_data(grading, None)['laser_data']
    assert verdict.passed, verdict.reason
    assert verdict.reason.endswith('seen 15 scans printed (8 needed), each a later scan than the one before, '
                                   'printed 1.0 to 1.0 ms after it was sent')
    [speed] = grading.turns
    assert grading.marks == [(0.9, 'fake_tb3 turns the robot at %.2f rad/s: the scans from here are judged' % speed,
                              'laser_data')]


def test_the_turn_speed_is_drawn_at_each_grading_either_way_round(grading, monkeypatch):
    # A printout stored from one grading shows the scans of its turn: no other grading turns alike.
    seeds = iter(range(12))
    monkeypatch.setattr(common.random, 'SystemRandom', lambda: random.Random(next(seeds)))
    grading.sent = scans(20)
    grading.output, grading.turned = printed(grading.sent), 0.9
    for _ in range(12):
        move_turtlebot3.check_laser_data(grading, None)
    assert all(0.5 <= abs(speed) <= 1.5 for speed in grading.turns)
    assert len(set(grading.turns)) == 12 and min(grading.turns) < 0 < max(grading.turns)


def test_a_turn_fake_tb3_never_applied_judges_nothing(grading):
    # Every block the scan of its moment, as a stored printout of a robot standing still would be.
    grading.sent = scans(20)
    grading.output, grading.turned = printed(grading.sent), None
    verdict = move_turtlebot3.check_laser_data(grading, None)['laser_data']
    assert not verdict.passed
    assert verdict.reason.endswith("seen: fake_tb3 never applied the grader's turn (its record holds no command of "
                                   'the grader), so no scan it sent can be told from a stored one')


def test_blocks_printed_only_before_the_turn_count_for_nothing(grading):
    grading.sent = scans(20)
    grading.output, grading.turned = printed(grading.sent[:10]), 2.5
    verdict = move_turtlebot3.check_laser_data(grading, None)['laser_data']
    assert not verdict.passed
    assert verdict.reason.endswith('seen: 10 scans printed, none once fake_tb3 turned the robot (2.5 simulated s)')


def test_the_run_waits_for_the_blocks_needed_after_a_late_turn(grading):
    # A machine that delayed the turn to 2.5 simulated s: 20 blocks printed, 7 of them after it.
    grading.sent = scans(20)
    grading.output, grading.turned = printed(grading.sent), 2.5
    verdict = move_turtlebot3.check_laser_data(grading, None)['laser_data']
    assert grading.waited == [False]   # the run goes on (here it ends: no more scans come)
    assert verdict.reason.endswith('seen 7 scans printed (8 needed), each a later scan than the one before, '
                                   'printed 1.0 to 1.0 ms after it was sent')
    grading.sent = scans(30)
    grading.output, grading.waited = printed(grading.sent), []
    assert move_turtlebot3.check_laser_data(grading, None)['laser_data'].passed
    assert grading.waited == [True]
