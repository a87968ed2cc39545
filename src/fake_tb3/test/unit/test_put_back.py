"""The grader's put-back (fake_tb3.put_back): a robot that drove and stood still is put back along
its heading, once; a node that answers its scans drives and stops again, one that drives by the
clock does not."""
import math
import os

import pytest

from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.put_back import PutBack, SettingsError, from_settings
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import World, load_world

WORLDS = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds')
DT = 0.01          # s, fake_tb3's physics step
SCAN_EVERY = 20    # steps: 5 scans a second


def spawn(world, x=-2.0, y=-0.5, yaw=0.0):
    robot = SimRobot('', get_model('burger'), x, y, yaw, Laser(noise_stddev=0.0))
    return Simulation(world, [robot]), robot


def run(simulation, robot, put_back, seconds, drive):
    """Steps `seconds`; drive(step, front beam) gives the command at each scan. Returns the events
    put_back told, with the simulated time of each, and the front beam at each scan."""
    events, fronts = [], []
    for step in range(int(round(seconds / DT))):
        if step % SCAN_EVERY == 0:
            front = simulation.scan(robot)[0]
            fronts.append((simulation.time, front))
            command = drive(simulation.time, front)
            if command is not None:
                simulation.command(robot, command, 0.0)
        simulation.step(DT)
        event = put_back.after_step(simulation)
        if event:
            events.append((simulation.time, event))
    return events, fronts


def slide_node(_time, front):
    """avoid_obstacle.py of the slides: forward while the front beam reads more than 0.5 m."""
    return 0.5 if front > 0.5 else 0.0


def test_the_slide_node_drives_and_stops_again_once_put_back():
    simulation, robot = spawn(load_world('turtlebot3_world', WORLDS))
    put_back = PutBack(robot, min_drive=0.5, after=6.3, distance=0.9)
    events, fronts = run(simulation, robot, put_back, 30.0, slide_node)
    assert len(events) == 1
    at, event = events[0]
    first_stop = event['from']
    assert first_stop[0] > -1.5 and at - event['still_since'] == pytest.approx(6.3, abs=DT)
    # 0.9 m straight back along its heading (0 rad), the heading kept.
    assert event['to'] == pytest.approx((first_stop[0] - 0.9, first_stop[1], first_stop[2]), abs=1e-12)
    # It drove again to where the first scan under 0.5 m stopped it: the same stop, a front beam
    # under 0.5 m both times.
    assert robot.pose[0] == pytest.approx(first_stop[0], abs=0.11) and robot.pose[0] > event['to'][0] + 0.7
    before = [front for time, front in fronts if time < at]
    assert 0.35 < before[-1] <= 0.5 and 0.35 < fronts[-1][1] <= 0.5


def test_a_drive_by_the_clock_stays_where_it_is_put():
    simulation, robot = spawn(load_world('turtlebot3_world', WORLDS))
    put_back = PutBack(robot, min_drive=0.5, after=5.0, distance=0.6)
    events, _ = run(simulation, robot, put_back, 25.0, lambda time, _front: 0.5 if time < 8.55 else 0.0)
    assert len(events) == 1
    assert robot.pose == pytest.approx(events[0][1]['to'])


def test_it_waits_for_the_drive_and_a_still_stretch_and_comes_once():
    simulation, robot = spawn(World('empty'), x=0.0, y=0.0)
    put_back = PutBack(robot, min_drive=0.5, after=2.0, distance=0.3)
    # Standing at the spawn pose for 5 s: not driven, no put-back.
    assert run(simulation, robot, put_back, 5.0, lambda *_: 0.0)[0] == []
    # 0.4 m, 2 s still, 0.2 m more (0.6 m from the spawn), 1.5 s still, then 0.2 m on: still not.
    plan = [(0.8, 0.5), (2.0, 0.0), (0.4, 0.5), (1.5, 0.0), (0.4, 0.5)]
    for seconds, speed in plan:
        assert run(simulation, robot, put_back, seconds, lambda *_, speed=speed: speed)[0] == []
    events, _ = run(simulation, robot, put_back, 4.0, lambda *_: 0.0)
    assert [round(at - event['still_since'], 6) for at, event in events] == [2.0]
    assert robot.pose == pytest.approx((0.5, 0.0, 0.0), abs=1e-9)
    assert run(simulation, robot, put_back, 4.0, lambda *_: 0.0)[0] == []   # once


def test_where_the_place_behind_is_taken_the_robot_goes_back_to_its_spawn_pose():
    # The body reaches 0.102 m behind the robot's x: at 0.6 it would overlap the wall.
    wall = {'type': 'polygon', 'points': [[0.45, -1.0], [0.45, 1.0], [0.55, 1.0], [0.55, -1.0]]}
    simulation, robot = spawn(World('wall', [wall]), x=1.0, y=0.0)
    put_back = PutBack(robot, min_drive=0.5, after=1.0, distance=1.0)
    events, _ = run(simulation, robot, put_back, 4.0, lambda time, _: 0.5 if time < 1.2 else 0.0)
    assert events[0][1]['to'] == pytest.approx((1.0, 0.0, 0.0))
    assert not simulation.place(robot, 0.6, 0.0, 0.0) and robot.pose == pytest.approx((1.0, 0.0, 0.0))
    assert not simulation.place(robot, math.nan, 0.0, 0.0)


@pytest.mark.parametrize('text, reason', [
    ('{', "the grader's settings are not JSON"),
    ('[1]', "the grader's settings must be a JSON object, got [1]"),
    ('{"put_back": {"after": 5, "distance": 1}}', 'put_back must be an object of min_drive, after and distance'),
    ('{"put_back": {"after": 5, "distance": -1, "min_drive": 0.5}}', 'put_back distance must be a positive number, got -1'),
    ('{"put_back": {"after": true, "distance": 1, "min_drive": 0.5}}', 'put_back after must be a positive number, got True'),
    ('{"put_back": {"after": 1e999, "distance": 1, "min_drive": 0.5}}', 'put_back after must be a positive number, got inf'),
])
def test_bad_settings_are_refused_with_the_reason(text, reason):
    with pytest.raises(SettingsError, match='^' + reason.replace('[', r'\[').replace(']', r'\]')):
        from_settings(text)


def test_no_settings_no_put_back():
    assert from_settings('') is None and from_settings('{}') is None
    assert from_settings('{"put_back": {"after": 5, "distance": 0.5, "min_drive": 0.5}}') == {
        'after': 5, 'distance': 0.5, 'min_drive': 0.5}
