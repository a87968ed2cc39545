#!/usr/bin/env python3
"""`roslaunch course_web replay.launch bag:=RUN.bag` on bags the grader's code writes
(course_grader.bags, from a simulator's record): the run plays on simulated time under the
simulator's name, and the live view draws it as if live: fake_tb3's robot on its pose, turtlesim's
turtle with the trail in the pen's colour (a record of the course's turtlesim, its pen set). A bag that is no bag is one sentence, and nothing runs."""
import base64
import io
import json
import os
import shutil
import signal
import struct
import subprocess
import tempfile
import time
import unittest

import rosgraph
import rospy
import rostest
import tornado.httpclient
import tornado.ioloop
import tornado.websocket
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from PIL import Image

from course_common import sim_record
from course_common.sim_record import RecordReader, RecordWriter
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from course_testing.processes import LoggedLaunch
from course_web.ros_view import served_port
from course_grader import bags
from turtlesim.msg import Pose
from turtlesim.srv import SetPen

PX_PER_METRE = 500 / 11.088889   # turtlesim's canvas


def write_record(path, entries):
    writer = RecordWriter(path)
    for name, sim_ns, payload in entries:
        if isinstance(payload, dict):
            writer.event(name, sim_ns, 0.0, **payload)
        else:
            writer.write(name, sim_ns, 0.0, payload)
    writer.close()
    return RecordReader(path).read_new()


def fake_tb3_bag(folder):
    """3 simulated seconds of the burger driving from (-2, -0.5) along x at 0.2 m/s."""
    pose = struct.Struct('<5d')
    entries = [('collisions', 0, {'robot': '', 'count': 0})]
    entries += [('pose', n * 33333333, pose.pack(-2.0 + 0.2 * n / 30, -0.5, 0.0, 0.2, 0.0)) for n in range(91)]
    path = os.path.join(folder, 'avoid_obstacle.bag')
    bags.write_bag(path, bags.fake_tb3_messages(write_record(os.path.join(folder, 'tb3.record'), entries),
                                                world='turtlebot3_world', model='burger'))
    return path


def turtlesim_bag(folder):
    """The course's turtlesim recording for the grader (COURSE_SIM_RECORD): turtle1's pen set red
    and 4 wide, then driven along x until past x 7.3; the record kept as a bag by
    course_grader.bags, as the grader keeps a run. (bag, turtle1's last pose)"""
    record = os.path.join(folder, 'turtlesim.record')
    turtlesim = subprocess.Popen(['rosrun', 'turtlesim', 'turtlesim_node'], stdin=subprocess.DEVNULL,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                 env=dict(os.environ, **{sim_record.ENVIRONMENT: record}))
    try:
        rospy.wait_for_service('/turtle1/set_pen', 30)
        rospy.ServiceProxy('/turtle1/set_pen', SetPen)(255, 0, 0, 4, 0)
        drive = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
        poses = TopicRecorder('/turtle1/pose', Pose)
        wait_until(lambda: drive.get_num_connections() and poses.count(), 30, 'turtlesim to listen and publish')

        def driven_past():
            drive.publish(Twist(linear=Vector3(x=2.0)))
            return poses.latest().x > 7.3
        wait_until(driven_past, 30, 'turtle1 to drive past x 7.3', poll=0.1)
        drive.unregister()
        poses.close()
    finally:
        turtlesim.send_signal(signal.SIGINT)
        turtlesim.wait(30)
    entries = sim_record.RecordReader(record).read_new()
    path = os.path.join(folder, 'exercise3.bag')
    bags.write_bag(path, bags.turtlesim_messages(entries, '/turtlesim'))
    last = Pose().deserialize([entry for entry in entries if entry.name == '/turtle1/pose'][-1].payload)
    return path, last


def page_frames(port, wanted, seconds=30):
    """The frames the view sends a page from now until wanted(frame) (that frame), or None."""
    async def read():
        request = tornado.httpclient.HTTPRequest('ws://127.0.0.1:%d/ws' % port,
                                                 headers={'Origin': 'http://127.0.0.1:%d' % port})
        page = await tornado.websocket.websocket_connect(request)
        end = time.monotonic() + seconds
        try:
            while time.monotonic() < end:
                message = await page.read_message()
                if message is None:
                    return None
                frame = json.loads(message)
                if wanted(frame):
                    return frame
        finally:
            page.close()
        return None
    loop = tornado.ioloop.IOLoop()
    try:
        return loop.run_sync(read)
    finally:
        loop.close()


class ReplayTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix='replay-test-')
        self.addCleanup(shutil.rmtree, self.folder, True)   # after tearDown has stopped the replay
        self.port = None
        self.launch = None

    def tearDown(self):
        if self.launch:
            self.launch.stop(30)

    def replay(self, bag, *args):
        # The view on port 0, at the port it says: a port found free here could be taken before the
        # view listens, and whatever listened there would answer for it (seen: a reset connection).
        self.launch = LoggedLaunch(['roslaunch', 'course_web', 'replay.launch', 'bag:=' + bag, 'port:=0'] + list(args),
                                   os.path.join(self.folder, 'replay.log'), os.environ)
        self.port = wait_until(lambda: self._serving(), 60, 'the view of the replay to say where it serves', poll=0.2)

    def _serving(self):
        self.assertFalse(self.launch.exited(), 'roslaunch ended:\n' + self.launch.output())
        return served_port(self.launch.output())

    def stop(self):
        """Ctrl-C: the launch, the playback and the redraw end."""
        self.launch.stop(30)
        output = self.launch.output()
        master = rosgraph.Master('/replay_test')
        wait_until(lambda: not ({'/fake_tb3', '/turtlesim', '/replay_play', '/course_web'} & {
            node for _, nodes in master.getSystemState()[0] for node in nodes}), 10, 'the replay to leave the graph')
        return output

    def test_a_fake_tb3_bag_plays_as_fake_tb3_and_the_view_draws_the_robot(self):
        self.replay(fake_tb3_bag(self.folder))
        odom = rospy.wait_for_message('/odom', Odometry, 30)
        self.assertEqual(odom.header.frame_id, 'odom')
        self.assertTrue(-2.0 <= odom.pose.pose.position.x <= -1.4)
        publishers = dict((topic, nodes) for topic, nodes in rosgraph.Master('/replay_test').getSystemState()[0])
        self.assertEqual(publishers['/odom'], ['/fake_tb3'])
        self.assertIn('/clock', publishers)
        self.assertEqual(rospy.get_param('/fake_tb3/world'), 'turtlebot3_world')
        worlds = []   # the page gets the world once, then the robot's poses

        def robot_in_its_world(frame):
            part = frame.get('tb3') or {}
            worlds.extend([part['world']] if part.get('world') else [])
            return bool(worlds and part.get('pose'))
        frame = page_frames(self.port, robot_in_its_world)
        self.assertIsNotNone(frame, 'the page never drew the replayed robot in its world')
        x, y, _ = frame['tb3']['pose']
        self.assertTrue(-2.0 <= x <= -1.4 and abs(y + 0.5) < 1e-3, frame['tb3']['pose'])
        self.assertIn('replay: playing %s (fake_tb3, again and again)' % os.path.join(self.folder, 'avoid_obstacle.bag'),
                      self.stop())

    def test_a_turtlesim_run_is_redrawn_with_its_pen(self):
        bag, last = turtlesim_bag(self.folder)
        self.replay(bag, 'loop:=false')
        wait_until(lambda: '/turtlesim/scene' in dict(rosgraph.Master('/replay_test').getSystemState()[0]), 30,
                   'the redrawn turtlesim\'s ~scene')
        # A first page watches the run to its end; a page opened then gets it all in its first picture.
        def at_the_end(frame):
            turtles = (frame.get('turtlesim') or {}).get('turtles') or []
            return any(turtle[0] == 'turtle1' and abs(turtle[1] - last.x) < 1e-3 for turtle in turtles)
        self.assertIsNotNone(page_frames(self.port, at_the_end), 'the page never saw turtle1 at the end of the run')
        frame = page_frames(self.port, lambda frame: (frame.get('turtlesim') or {}).get('canvas'))
        self.assertIsNotNone(frame, 'the page never got turtlesim\'s canvas')
        turtles = {turtle[0]: turtle for turtle in frame['turtlesim']['turtles']}
        self.assertEqual(sorted(turtles), ['turtle1'])
        self.assertAlmostEqual(turtles['turtle1'][1], last.x, places=3)
        canvas = Image.open(io.BytesIO(base64.b64decode(frame['turtlesim']['canvas'].split(',', 1)[1]))).convert('RGB')
        row = int(round((11.088889 - 5.544445) * PX_PER_METRE))
        middle = int((5.544445 + last.x) / 2 * PX_PER_METRE)
        self.assertEqual(canvas.getpixel((middle, row)), (255, 0, 0))             # the trail, in the pen's red
        self.assertEqual(canvas.getpixel((middle, row + 20)), (69, 86, 255))      # turtlesim's background
        self.assertEqual(canvas.getpixel((int((last.x + 1) * PX_PER_METRE), row)), (69, 86, 255))   # beyond it
        self.stop()

    def test_a_file_that_is_no_bag_is_one_sentence_and_nothing_runs(self):
        path = os.path.join(self.folder, 'notes.bag')
        with open(path, 'w') as stream:
            stream.write('not a bag')
        launch = subprocess.run(['roslaunch', 'course_web', 'replay.launch', 'bag:=' + path, 'port:=0'],
                                stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True, timeout=120)
        self.assertIn('replay: cannot read %s: This does not appear to be a bag file' % path, launch.stdout)
        self.assertIn('REQUIRED process [replay-', launch.stdout)


if __name__ == '__main__':
    rospy.init_node('replay_test')
    rostest.rosrun('course_grader', 'replay_launch', ReplayTest)
