"""A run's bag from the simulator's own record (course_grader.bags): the simulator's topics with the
real message types at the recorded simulated times, the commands with their senders, the pen;
bounded; a bag that cannot be written is an OSError naming it and leaves no file. No master."""
import json
import os
import struct
import subprocess
import sys

import pytest
import rosbag
import rospy
from sensor_msgs.msg import LaserScan

from course_common.sim_record import RecordWriter
from course_grader import bags

FAKE_TB3_POSE = struct.Struct('<5d')


def record(path, entries):
    """A record file of (name, sim ns, payload bytes or a dict for an event)."""
    writer = RecordWriter(path)
    for index, (name, sim_ns, payload) in enumerate(entries):
        if isinstance(payload, dict):
            writer.event(name, sim_ns, float(index), **payload)
        else:
            writer.write(name, sim_ns, float(index), payload)
    writer.close()
    return bags.read_record(path)


def scan_bytes(front, stamp_ns):
    scan = LaserScan(angle_min=0.0, angle_max=6.26, angle_increment=0.0174533, range_min=0.12, range_max=3.5,
                     ranges=[front] + [1.5] * 359, intensities=[0.0] * 360)
    scan.header.stamp = rospy.Time(0, stamp_ns)
    scan.header.frame_id = 'base_scan'
    return scan


def serialized(message):
    import io
    buffer = io.BytesIO()
    message.serialize(buffer)
    return buffer.getvalue()


def order(messages):
    """(topic, type, time ns) of each message, sorted by time then topic."""
    return sorted((topic, message._type, t.to_nsec()) for topic, message, t, _ in messages)


def fake_tb3_record(tmp_path):
    scan = scan_bytes(0.45, 200000000)
    return record(str(tmp_path / 'sim.record'), [
        ('pose', 0, FAKE_TB3_POSE.pack(-2.0, -0.5, 0.0, 0.0, 0.0)),
        ('collisions', 0, {'robot': '', 'count': 0}),
        ('command', 100000000, {'robot': '', 'linear': 0.2, 'angular': 0.0,
                                'sender': '/obstacle_avoidance (uid 1000)', 'nodes': ['/obstacle_avoidance']}),
        ('pose', 133333333, FAKE_TB3_POSE.pack(-1.99, -0.5, 0.5, 0.2, 0.0)),
        ('scan', 200000000, serialized(scan)),
        ('collisions', 300000000, {'robot': '', 'count': 1}),
        ('service_call', 400000000, {'service': '/fake_tb3/save_picture', 'caller': '/x'}),
    ]), scan


def test_fake_tb3_topics_types_and_simulated_times(tmp_path):
    entries, scan = fake_tb3_record(tmp_path)
    path = str(tmp_path / 'avoid_obstacle.bag')
    bags.write_bag(path, bags.fake_tb3_messages(entries, world='turtlebot3_world', model='burger'))
    with rosbag.Bag(path) as bag:
        read = list(bag.read_messages(return_connection_header=True))
    assert order(read) == order([(topic, message, t, None) for topic, message, t, _ in [
        # At simulated time 0 a message is stored at 1 ns: rosbag play skips those at 0.
        ('/collisions', bags.UInt32(), rospy.Time(0, 1), None), ('/fake_tb3/run', bags.String(), rospy.Time(0, 1), None),
        ('/odom', bags.Odometry(), rospy.Time(0, 1), None), ('/cmd_vel', bags.Twist(), rospy.Time(0, 100000000), None),
        ('/odom', bags.Odometry(), rospy.Time(0, 133333333), None),
        ('/scan', LaserScan(), rospy.Time(0, 200000000), None),
        ('/collisions', bags.UInt32(), rospy.Time(0, 300000000), None),
        ('/fake_tb3/service_calls', bags.String(), rospy.Time(0, 400000000), None)]])
    by_topic = {}
    for topic, message, t, header in read:
        by_topic.setdefault(topic, []).append((message, header))
    assert json.loads(by_topic['/fake_tb3/run'][0][0].data) == {'world': 'turtlebot3_world', 'model': 'burger'}
    odom = by_topic['/odom'][1][0]
    assert (odom.header.stamp.to_nsec(), odom.header.frame_id, odom.child_frame_id) == (133333333, 'odom',
                                                                                       'base_footprint')
    assert (odom.pose.pose.position.x, odom.pose.pose.position.y, odom.twist.twist.linear.x) == (-1.99, -0.5, 0.2)
    assert odom.pose.pose.orientation.z == pytest.approx(0.24740, abs=1e-5)   # sin(0.25)
    command, header = by_topic['/cmd_vel'][0]
    assert (command.linear.x, command.angular.z, header['callerid']) == (0.2, 0.0, b'/obstacle_avoidance (uid 1000)')
    # The scan is the bytes fake_tb3 sent, to the last bit.
    assert serialized(by_topic['/scan'][0][0]) == serialized(scan)
    assert [message.data for topic, message, _, _ in read if topic == '/collisions'] == [0, 1]
    assert bags.collisions(entries) == [(pytest.approx(0.3), 1)]


def test_turtlesim_poses_commands_pen_and_canvas(tmp_path):
    pose = struct.Struct('<5f')
    entries = record(str(tmp_path / 'ts.record'), [
        ('/turtle1/pose', 16000000, pose.pack(5.544445, 5.544445, 0.0, 0.0, 0.0)),
        ('clear', 16000000, {'background': [69, 86, 255]}),
        ('turtles', 16000000, {'names': ['turtle1']}),
        ('command', 16000000, {'turtle': 'turtle1', 'linear': 1.0, 'angular': 1.0, 'sender': '/circle (uid 1000)',
                               'nodes': ['/circle']}),
        ('pen', 32000000, {'turtle': 'turtle1', 'r': 255, 'g': 0, 'b': 0, 'width': 4, 'off': False}),
        ('/turtle1/pose', 32000000, pose.pack(5.56, 5.545, 0.016, 1.0, 1.0)),
        ('pen', 48000000, {'turtle': 'turtle1', 'r': 0, 'g': 0, 'b': 0, 'width': 0, 'off': True}),
    ])
    path = str(tmp_path / 'exercise3.bag')
    bags.write_bag(path, bags.turtlesim_messages(entries, '/turtlesim'))
    with rosbag.Bag(path) as bag:
        read = list(bag.read_messages(return_connection_header=True))
    assert [item for item in order(read)] == sorted([
        ('/turtle1/pose', 'turtlesim/Pose', 16000000), ('/turtlesim/canvas', 'std_msgs/String', 16000000),
        ('/turtlesim/turtles', 'std_msgs/String', 16000000), ('/turtle1/cmd_vel', 'geometry_msgs/Twist', 16000000),
        ('/turtle1/pen', 'turtlesim/SetPenRequest', 32000000), ('/turtle1/pose', 'turtlesim/Pose', 32000000),
        ('/turtle1/pen', 'turtlesim/SetPenRequest', 48000000)])
    by_topic = {}
    for topic, message, t, header in read:
        by_topic.setdefault(topic, []).append((message, header))
    moved = by_topic['/turtle1/pose'][1][0]
    assert moved.linear_velocity == 1.0 and moved.x == pytest.approx(5.56)
    assert by_topic['/turtle1/cmd_vel'][0][1]['callerid'] == b'/circle (uid 1000)'
    assert [(pen.r, pen.width, pen.off) for topic, pen, _, _ in read if topic == '/turtle1/pen'] == [(255, 4, 0),
                                                                                                 (0, 0, 1)]
    assert json.loads(by_topic['/turtlesim/canvas'][0][0].data) == {'background': [69, 86, 255]}


def test_a_turtlesim_in_a_namespace_names_its_turtles_topics_as_it_did(tmp_path):
    pose = struct.Struct('<5f')
    entries = record(str(tmp_path / 'ts.record'), [
        ('/sim/turtle1/pose', 16000000, pose.pack(1, 2, 0, 0, 0)),
        ('command', 16000000, {'turtle': 'turtle1', 'linear': 1.0, 'angular': 0.0, 'sender': '/a (uid 1)',
                               'nodes': ['/a']}),
        ('command', 16000000, {'turtle': 'robotics', 'linear': 1.0, 'angular': 0.0, 'sender': '/a (uid 1)',
                               'nodes': ['/a']})])
    topics = [topic for topic, _, _, _ in bags.turtlesim_messages(entries, '/sim/turtlesim')]
    assert topics == ['/sim/turtle1/pose', '/sim/turtle1/cmd_vel', '/sim/robotics/cmd_vel']


def test_a_topic_over_its_cap_keeps_an_even_sample_with_its_first_and_last():
    messages = [('/scan', None, rospy.Time(0, n), None) for n in range(2000)] + [
        ('/cmd_vel', None, rospy.Time(0, n), None) for n in range(10)]
    kept = bags.bounded(messages)
    scans = [t.to_nsec() for topic, _, t, _ in kept if topic == '/scan']
    assert len(scans) == bags.TOPIC_CAPS['scan'] and scans[0] == 0 and scans[-1] == 1999
    assert max(b - a for a, b in zip(scans, scans[1:])) <= 4
    assert len([1 for topic, _, _, _ in kept if topic == '/cmd_vel']) == 10
    many = [('/t%d/pose' % n, None, rospy.Time(0, 1), None) for n in range(bags.MAX_TOPICS + 5)]
    assert len(bags.bounded(many)) == bags.MAX_TOPICS
    # 30 turtles over a long run: every topic keeps its share of MAX_MESSAGES.
    crowd = [('/t%d/pose' % k, None, rospy.Time(0, n), None) for n in range(3000) for k in range(30)]
    kept = bags.bounded(crowd)
    assert bags.MAX_MESSAGES - 30 <= len(kept) <= bags.MAX_MESSAGES
    assert len([1 for topic, _, _, _ in kept if topic == '/t29/pose']) == bags.MAX_MESSAGES // 30


def test_marks_sorted_by_time(tmp_path):
    path = str(tmp_path / 'avoid_obstacle.marks.json')
    bags.write_marks(path, [bags.mark(12.5, 'stopped', 'avoid_stops'), bags.mark(3.25, 'collision 1', 'avoid_stays')])
    with open(path) as stream:
        assert json.load(stream) == [{'t': 3.25, 'what': 'collision 1', 'criterion': 'avoid_stays'},
                                     {'t': 12.5, 'what': 'stopped', 'criterion': 'avoid_stops'}]


def test_an_existing_file_or_a_link_is_never_written_through(tmp_path):
    target = tmp_path / 'result.json'
    target.write_text('{}')
    os.symlink(str(target), str(tmp_path / 'run.bag'))
    with pytest.raises(OSError, match='cannot write run.bag'):
        bags.write_bag(str(tmp_path / 'run.bag'), [])
    assert target.read_text() == '{}' and os.path.islink(str(tmp_path / 'run.bag'))


FULL_DISK = r'''
import resource, signal, sys
from course_grader import bags
from test_bags import fake_tb3_record
import pathlib
entries, _ = fake_tb3_record(pathlib.Path(sys.argv[1]))
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (8192, 8192))   # as a disk with 8 KiB left
messages = bags.fake_tb3_messages(entries * 20, world='turtlebot3_world', model='burger')
try:
    bags.write_bag(sys.argv[1] + '/run.bag', messages)
except OSError as error:
    print(error)
'''


def test_a_bag_that_cannot_be_written_is_an_oserror_naming_it_and_leaves_no_file(tmp_path):
    printed = subprocess.run([sys.executable, '-c', FULL_DISK, str(tmp_path)], check=True, stdout=subprocess.PIPE,
                             cwd=os.path.dirname(__file__), universal_newlines=True).stdout
    assert printed.startswith('cannot write run.bag: File too large'), printed
    assert not os.path.exists(str(tmp_path / 'run.bag'))


def test_the_session_notes_a_bag_it_cannot_write_and_goes_on(tmp_path, capsys):
    from course_grader.grading_session import Session
    session = Session(None, str(tmp_path), str(tmp_path), None)
    session.bags_dir = str(tmp_path / 'missing')   # as a disk that refuses it
    session.keep_run('trajectory', lambda: [])
    session.keep_marks('trajectory', [])

    def broken():
        raise ValueError('a record cut short')
    session.bags_dir = str(tmp_path)
    session.keep_run('laser_data', broken)
    assert session.notes == [
        'the run trajectory was not kept as trajectory.bag (cannot write trajectory.bag: No such file or '
        'directory); its criteria stand',
        'the moments judged in the run trajectory were not kept (cannot write trajectory.marks.json: No such '
        'file or directory); its criteria stand',
        'the run laser_data was not kept as laser_data.bag (a record cut short); its criteria stand']
    assert 'grade_submission note: the run laser_data was not kept' in capsys.readouterr().err
    assert os.listdir(str(tmp_path)) == []


def test_a_bag_not_made_in_time_is_an_oserror_and_leaves_no_file(tmp_path):
    entries, _ = fake_tb3_record(tmp_path)
    with pytest.raises(OSError, match='cannot write run.bag: not written within 5 s'):
        bags.write_bag(str(tmp_path / 'run.bag'), bags.fake_tb3_messages(entries), deadline=0.0)
    assert not os.path.exists(str(tmp_path / 'run.bag'))
