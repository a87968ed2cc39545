"""avoid_stops asks for the stop twice: from the spawn pose, and once fake_tb3 put the robot back at
a moment and by a distance the grader drew (fake_tb3.put_back). A node that drives by the clock,
tuned to the spawn pose, stops in the band once and stays where it is put."""
import types

import pytest
from sensor_msgs.msg import LaserScan

from course_grader import rubric
from course_grader.labs import move_turtlebot3

import fake_runs

WALL_X = 2.645   # m: where the front beam meets the obstacle ahead of the spawn pose (-2, -0.5)
RUBRIC = rubric.load('move_turtlebot3')


def timeline(*legs):
    """Poses (sim s, x, y, yaw) at fake_tb3's odometry rate (30 Hz) along legs (seconds, speed m/s,
    or 'to', x): driving straight along y = -0.5 from x = -2."""
    poses, t, x = [(0.0, -2.0, -0.5, 0.0)], 0.0, -2.0
    for leg in legs:
        if leg[0] == 'to':
            x = leg[1]
            continue
        seconds, speed = leg
        for _ in range(int(round(seconds * 30))):
            t += 1 / 30
            x += speed / 30
            poses.append((t, x, -0.5, 0.0))
    return poses


def scans_of(poses):
    """A scan every 0.2 simulated s, its front beam the distance to the wall."""
    scans = []
    for t, x, _, _ in poses[5::6]:
        scan = LaserScan(ranges=[WALL_X - x] + [3.5] * 359)
        scan.header.stamp.secs, scan.header.stamp.nsecs = divmod(int(round(t * 1e9)), 1000000000)
        scans.append(scan)
    return scans


class FakeRun(fake_runs.FakeRun):
    """What check_avoid_obstacle asks of its Run, over a run recorded beforehand: the watch shows
    what fake_tb3 recorded up to a moment, which each wait moves on, a pose at a time, until its
    condition holds (or the record ends)."""

    def __init__(self, session, simulators, script, grader_settings=None, **sim_args):
        session.settings, session.sim_args = grader_settings, sim_args
        shown = [1]   # how many of the poses were recorded so far

        def poses():
            return session.poses[:shown[0]]

        def put_back():
            return session.put if session.put and session.put[0] <= poses()[-1][0] else None

        def wait(condition, gave_up=None):
            while not condition() and shown[0] < len(session.poses):
                shown[0] += 1
            return condition()
        self.node = types.SimpleNamespace(name=script, explain=lambda: [], ended=lambda: session.ended)
        self.deadline = types.SimpleNamespace(wait=wait)
        self.watch = types.SimpleNamespace(
            copy=lambda name: {'poses': poses, 'scans': lambda: scans_of(poses()),
                               'commands': lambda: [(0.0, 0.5, 0.0)]}[name](),
            poses_since=lambda start: [pose for pose in poses() if pose[0] >= start],
            now=lambda: poses()[-1][0], put_back=put_back, collisions=0,
            front_range=lambda: scans_of(poses())[-1].ranges[0])
        self.marks = session.marks



@pytest.fixture
def grading(monkeypatch):
    session = types.SimpleNamespace(rubric=RUBRIC, marks=[], ended=False, put=None)
    monkeypatch.setattr(move_turtlebot3, 'Run', FakeRun)
    return session


def put_back(at, x, to_x, still_since):
    return (at, {'still_since': still_since, 'x': x, 'y': -0.5, 'to_x': to_x, 'to_y': -0.5})


def test_a_node_that_answers_its_scans_stops_twice(grading):
    # 4.2 m to the stop (front beam 0.445 m), 6 s still, put back 0.9 m, off again at once.
    grading.poses = timeline((8.4, 0.5), (6.0, 0.0), ('to', 1.3), (0.1, 0.0), (1.8, 0.5), (2.0, 0.0))
    grading.put = put_back(14.4, 2.2, 1.3, 8.4)
    outcomes = move_turtlebot3.check_avoid_obstacle(grading, None)
    assert outcomes['avoid_stops'].passed and outcomes['avoid_stays'].passed
    assert outcomes['avoid_stops'].reason.endswith(
        'seen: it drove 4.20 m and stopped with the front beam at 0.445 m (median over the stop); put back 0.90 m '
        'after 6.0 s standing still, it drove again 0.1 s later and stopped with the front beam at 0.445 m (median '
        'over the stop)')
    assert [mark for mark in grading.marks if 'puts the robot back' in mark[1]] == [
        (14.4, 'the grader puts the robot back 0.90 m: it must drive and stop again', 'avoid_stops')]
    # The moment and the distance, drawn within the rubric's bounds, went to fake_tb3 as the
    # grader's settings, none as a parameter of the master.
    drawn = grading.settings['put_back']
    assert 5.0 <= drawn['after'] <= 15.0 and 0.3 <= drawn['distance'] <= 1.5 and drawn['min_drive'] == 0.5
    assert not any('put_back' in name or 'after' in name for name in grading.sim_args)


def test_a_drive_by_the_clock_stays_where_it_is_put(grading):
    grading.poses = timeline((8.4, 0.5), (6.0, 0.0), ('to', 1.3), (4.0, 0.0))
    grading.put = put_back(14.4, 2.2, 1.3, 8.4)
    outcomes = move_turtlebot3.check_avoid_obstacle(grading, None)
    assert not outcomes['avoid_stops'].passed and outcomes['avoid_stays'].passed
    assert outcomes['avoid_stops'].reason.endswith(
        'put back 0.90 m after 6.0 s standing still, it did not drive again within 2 s (a node that answers '
        'its scans drives on the next one)')


def test_a_node_that_drives_again_only_later_fails(grading):
    # A drive by the clock that guessed the distance but not the moment (3 s late).
    grading.poses = timeline((8.4, 0.5), (6.0, 0.0), ('to', 1.3), (3.0, 0.0), (1.8, 0.5), (2.0, 0.0))
    grading.put = put_back(14.4, 2.2, 1.3, 8.4)
    verdict = move_turtlebot3.check_avoid_obstacle(grading, None)['avoid_stops']
    assert not verdict.passed and verdict.reason.endswith('it did not drive again within 2 s (a node that answers '
                                                          'its scans drives on the next one)')


@pytest.mark.parametrize('ended, reason', [
    (True, 'avoid_obstacle.py ended before the grader could put the robot back'),
    (False, 'the grader puts the robot back once it stood still for'),
])
def test_no_put_back_no_points(grading, ended, reason):
    # Its stop in the band, and then it ended (or crept on) before fake_tb3 put it back.
    grading.poses, grading.ended = timeline((8.4, 0.5), (6.0, 0.0)), ended
    verdict = move_turtlebot3.check_avoid_obstacle(grading, None)['avoid_stops']
    assert not verdict.passed and reason in verdict.reason
