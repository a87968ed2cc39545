"""A run's bag as the report's player gets it (course_grader.replay): the live view's frames,
sampled, with whole frames to seek from and the judged moments; a bag that cannot be played is one
sentence in report.html and the grade stands. Bags written in a temporary folder, no master."""
import base64
import io
import json
import os
import sys

import numpy as np
import pytest
import rospy
from PIL import Image
from std_msgs.msg import String

from course_checks.verdict import Verdict
from course_grader import replay, reports, results, rubric
from turtlesim.world import PX_PER_METER, WORLD_SIZE

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import replay_bags  # noqa: E402 (the tests' bags, beside the rostests that use them too)


@pytest.fixture(scope='module')
def alice(tmp_path_factory):
    return replay_bags.write_class(str(tmp_path_factory.mktemp('grades')))


def data_of(folder, run):
    base = os.path.join(folder, run)
    return replay.replay_data(replay.read_bag(base + '.bag'), replay.read_marks(base + '.marks.json'))


def parts(data, name):
    return [json.loads(frame).get(name) for frame in data['frames']]


def test_the_robot_is_drawn_where_its_odometry_put_it_in_the_world_of_the_run(alice):
    data = data_of(alice, 'avoid_obstacle')
    tb3 = parts(data, 'tb3')
    assert tb3[0]['world']['name'] == 'turtlebot3_world' and tb3[0]['body']['model'] == 'burger'
    assert tb3[0]['pose'][:2] == list(replay_bags.TB3_SPAWN)
    assert json.loads(data['frames'][0])['turtlesim'] == {'present': False}
    end = replay_bags.TB3_SPAWN[0] + replay_bags.TB3_SPEED * replay_bags.TB3_STOP
    assert tb3[-1]['pose'][0] == pytest.approx(end, abs=1e-3)
    assert data['duration'] == pytest.approx(10.0, abs=0.05)
    # The scans (5 a second) as the live view draws them: the points 1 m around the laser.
    scans = [part['scan'] for part in tb3 if part.get('scan')]
    assert 50 <= len(scans) <= 51 and len(scans[-1]) == 360
    assert scans[-1][0] == pytest.approx([end + 1.0 - 0.032, -0.5], abs=0.002)   # laser 32 mm behind the centre
    # The path: the frames' trail points, one after another, are the robot's way, at least 1 cm
    # apart (two odometries of 6.7 mm here).
    trail = [point for part in tb3 for point in part['trail']]
    assert trail[0] == list(replay_bags.TB3_SPAWN) and trail[-1][0] == pytest.approx(end, abs=0.014)
    steps = [b[0] - a[0] for a, b in zip(trail, trail[1:])]
    assert len(trail) > 80 and all(0.0099 <= step <= 0.0145 for step in steps)


def test_frames_come_at_most_25_a_second_of_the_run_and_in_order(alice):
    data = data_of(alice, 'circle')
    times = data['times']
    assert times == sorted(times) and times[0] == 0 and data['duration'] == pytest.approx(8.0, abs=0.02)
    for second in range(8):
        assert sum(1 for t in times if second <= t < second + 1) <= replay.FRAMES_PER_SECOND + (second == 0)
    assert len(times) >= 8 * 20


def test_a_whole_frame_to_seek_from_every_2_s_is_what_a_page_that_connects_gets(alice):
    data = data_of(alice, 'avoid_obstacle')
    indices = sorted(data['keys'])
    seconds = [data['times'][i] for i in indices]
    assert len(indices) >= 3 and all(b - a >= replay.KEY_SECONDS - 1e-6 for a, b in zip([0.0] + seconds, seconds))
    for index in indices:
        whole = json.loads(data['keys'][index])['tb3']
        assert whole['trail_reset'] and whole['world']['name'] == 'turtlebot3_world'
        # All the path so far: the deltas' trail up to that frame.
        assert whole['trail'] == [point for part in parts(data, 'tb3')[:index + 1] for point in part['trail']]
        assert whole['pose'] == json.loads(data['frames'][index])['tb3']['pose']


def test_turtlesim_is_drawn_with_the_turtles_pen_on_its_canvas(alice):
    data = data_of(alice, 'circle')
    first = json.loads(data['frames'][0])
    assert json.loads(data['frames'][0])['tb3'] == {'present': False}
    turtlesim = first['turtlesim']
    assert turtlesim['turtles'][0][:3] == ['turtle1', 5.5, 3.5]
    lines = [op for part in parts(data, 'turtlesim') for op in part['ops']]
    assert lines and all(op[0] == 'line' and op[5:] == [255, 0, 0, 4] for op in lines)
    # The last whole frame's canvas: the circle drawn red where turtlesim draws it, the background
    # (69, 86, 255) inside it.
    last = json.loads(data['keys'][max(data['keys'])])['turtlesim']
    assert last['all'] and [t[0] for t in last['turtles']] == ['turtle1']
    png = base64.b64decode(last['canvas'].split(',', 1)[1])
    pixels = np.array(Image.open(io.BytesIO(png)).convert('RGB'))

    def pixel(x, y):
        return tuple(pixels[int(round((WORLD_SIZE - y) * PX_PER_METER)), int(round(x * PX_PER_METER))])
    assert pixel(5.5, 7.5) == (255, 0, 0)     # the top of the circle (after pi s)
    assert pixel(7.5, 5.5) == (255, 0, 0)     # its right (pi / 2 s)
    assert pixel(5.5, 5.5) == (69, 86, 255)   # its centre


def test_the_judged_moments_count_from_the_runs_first_picture(alice):
    circle, avoid = data_of(alice, 'circle'), data_of(alice, 'avoid_obstacle')
    assert circle['marks'] == [{'t': pytest.approx(6.283, abs=1e-3), 'what': 'a full turn driven: the circle closes',
                                'criterion': 'circle'}]
    assert [(m['t'], m['criterion']) for m in avoid['marks']] == [(pytest.approx(6.0), 'avoid_stops')]


def test_a_killed_turtle_leaves_the_picture(tmp_path):
    messages = replay_bags.turtlesim_messages(1.0)
    last_pose, last_time = messages[-1][1], messages[-1][2].to_sec()
    messages += [('/turtle2/pose', last_pose, rospy.Time.from_sec(last_time + 0.5), None),
                 ('/turtlesim/turtles', String('{"names": ["turtle2"]}'), rospy.Time.from_sec(last_time + 1), None),
                 ('/turtle2/pose', last_pose, rospy.Time.from_sec(last_time + 1.5), None)]
    replay_bags.write_run(str(tmp_path), 'kill', messages, [])
    data = data_of(str(tmp_path), 'kill')
    shown, seen = set(), []   # the turtles a page shows after each frame (as scene.js keeps them)
    for part in parts(data, 'turtlesim'):
        shown = set() if part.get('all') else shown - set(part.get('gone', []))
        shown |= {turtle[0] for turtle in part['turtles']}
        seen.append(sorted(shown))
    assert ['turtle1', 'turtle2'] in seen and seen[-1] == ['turtle2']


def test_a_long_run_is_thinned_to_the_size_bound(alice, monkeypatch):
    whole = data_of(alice, 'avoid_obstacle')
    size = sum(map(len, whole['frames'])) + sum(map(len, whole['keys'].values()))
    monkeypatch.setattr(replay, 'MAX_BYTES', size // 3)
    thinned = data_of(alice, 'avoid_obstacle')
    assert thinned['scan_stride'] > 1
    assert sum(map(len, thinned['frames'])) + sum(map(len, thinned['keys'].values())) <= size // 3
    assert thinned['duration'] == whole['duration']


def test_the_report_shows_a_player_per_run_from_files_beside_it(alice):
    out_dir = os.path.dirname(alice)
    section = replay.runs_html(out_dir, 'alice')
    assert section.count('<iframe') == 2
    assert 'src="_player/replay.html#alice/avoid_obstacle"' in section
    assert sorted(os.listdir(os.path.join(out_dir, '_player'))) == sorted(replay.PLAYER_FILES)
    with open(os.path.join(alice, 'circle.replay.js'), encoding='utf-8') as stream:
        statements = stream.read().splitlines()
    assert statements[0].startswith('window.courseReplay = {') and statements[0].endswith(';')
    head = json.loads(statements[0][len('window.courseReplay = '):-1])
    frames = json.loads(statements[1][len('window.courseReplay.frames = '):-1])
    assert head['run'] == 'circle' and len(frames) == len(head['times'])
    assert replay.runs_html(out_dir, 'nobody') == ''


def test_a_bag_that_cannot_be_read_is_one_sentence_and_the_grade_stands(tmp_path):
    folder = tmp_path / 'bob'
    folder.mkdir()
    (folder / 'avoid_obstacle.bag').write_bytes(b'#ROSBAG V2.0\nnot a bag at all')
    replay_bags.write_run(str(folder), 'circle', [m for m in replay_bags.turtlesim_messages(1.0) if m[0] != '/turtle1/pose'], [])
    rubric_ = rubric.load('move_turtlebot3')
    result = results.score(rubric_, {c.id: Verdict(True, 'ok') for c in rubric_.criteria}, 'bob', seconds=3)
    page = reports.html_report([result], rubric_, str(tmp_path))
    assert 'bob: 14 / 14' in page
    assert page.count('cannot be replayed') == 2 and '<iframe' not in page
    assert 'The run avoid_obstacle cannot be replayed: its bag cannot be read (' in page
    assert 'The run circle cannot be replayed: it holds no pose of a turtle' in page


def test_a_long_fast_run_keeps_its_whole_frames_within_the_bound(tmp_path, monkeypatch):
    """A minute at 1 m/s: each whole frame holds all of the path so far (up to 1800 points), 30 of
    them would be most of a bound of 400 kB: they come further apart, nothing else is thinned."""
    replay_bags.write_run(str(tmp_path), 'long', replay_bags.tb3_messages(60.0, speed=1.0, stop=60.0, scans=False), [])
    monkeypatch.setattr(replay, 'MAX_BYTES', 400000)
    data = data_of(str(tmp_path), 'long')
    assert data['duration'] == pytest.approx(60.0, abs=0.05)
    assert (data['frames_per_second'], data['scan_stride']) == (replay.FRAMES_PER_SECOND, 1)
    assert data['key_seconds'] == 2 * replay.KEY_SECONDS and 10 <= len(data['keys']) <= 15
    assert sum(map(len, data['frames'])) + sum(map(len, data['keys'].values())) <= replay.MAX_BYTES


def test_a_run_that_cannot_meet_the_bound_is_as_thin_as_it_goes_and_whole(alice, monkeypatch):
    monkeypatch.setattr(replay, 'MAX_BYTES', 1000)
    thinnest = data_of(alice, 'avoid_obstacle')
    assert (thinnest['scan_stride'], thinnest['frames_per_second'], thinnest['keys']) == (8, 5, {})
    assert thinnest['duration'] == pytest.approx(10.0, abs=0.05) and len(thinnest["frames"]) <= 10 * 5 + 2
