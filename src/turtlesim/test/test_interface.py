#!/usr/bin/env python3
"""turtlesim_node seen from outside: names and types, rate, timeout, log texts, services, pictures."""
import math
import os
import tempfile
import unittest

import rosgraph
import rospy
import rosservice
import rostest
from geometry_msgs.msg import Twist
from PIL import Image as PilImage
from sensor_msgs.msg import Image
from std_msgs.msg import String
from std_srvs.srv import Empty, Trigger

from course_common.service_calls import parse
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative
from turtlesim.world import TICK_SECONDS
from turtlesim_testing import (ONE_COMMAND_TICKS, RosoutWatcher, connected_publisher, graph, moved,
                               published_topics, twist)

WORLD_SIZE = 499 / 45  # metres; float32 poses may exceed it by 1e-6
BACKGROUND = (69, 86, 255)
NAN = float('nan')


def service(name, srv_type):
    rospy.wait_for_service(name, 10.0)
    return rospy.ServiceProxy(name, srv_type)


class TurtlesimInterfaceTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('turtlesim_interface_test')
        cls.rosout = RosoutWatcher()
        cls.reset = service('/reset', Empty)
        cls.clear = service('/clear', Empty)
        cls.spawn = service('/spawn', Spawn)
        cls.kill = service('/kill', Kill)

    def setUp(self):
        self.reset()
        self.pose = TopicRecorder('/turtle1/pose', Pose)
        self.pose.next_message(10.0)

    def tearDown(self):
        self.pose.close()

    def teleport(self, x, y, theta, name='turtle1'):
        service('/%s/teleport_absolute' % name, TeleportAbsolute)(x, y, theta)

    def assert_service_error(self, call, text):
        """The call fails, the client sees `text`, and the node logs it as an ERROR."""
        start = self.rosout.count()
        with self.assertRaises(rospy.ServiceException) as failure:
            call()
        self.assertIn(text, str(failure.exception))
        self.rosout.wait_for_line('ERROR', text, start, whole=False)

    # --- names and types ---
    def test_topics_services_and_params_have_the_original_names_and_types(self):
        topics = published_topics()
        self.assertEqual(topics['/turtle1/pose'], 'turtlesim/Pose')
        self.assertEqual(topics['/turtle1/color_sensor'], 'turtlesim/Color')
        self.assertEqual(topics['/turtlesim/canvas'], 'sensor_msgs/Image')
        _, subscribers, services = graph()
        self.assertEqual(subscribers['/turtle1/cmd_vel'], ['/turtlesim'])
        self.assertEqual(dict(rosgraph.Master('/t').getTopicTypes())['/turtle1/cmd_vel'], 'geometry_msgs/Twist')
        expected_services = {
            '/clear': 'std_srvs/Empty', '/reset': 'std_srvs/Empty', '/spawn': 'turtlesim/Spawn',
            '/kill': 'turtlesim/Kill', '/turtle1/set_pen': 'turtlesim/SetPen',
            '/turtle1/teleport_absolute': 'turtlesim/TeleportAbsolute',
            '/turtle1/teleport_relative': 'turtlesim/TeleportRelative',
            '/turtlesim/save_canvas': 'std_srvs/Trigger'}
        for name, srv_type in expected_services.items():
            self.assertEqual(services[name], ['/turtlesim'], name)
            self.assertEqual(rosservice.get_service_type(name), srv_type, name)
        for channel, value in zip('rgb', BACKGROUND):
            self.assertEqual(rospy.get_param('/turtlesim/background_' + channel), value)
        self.assertEqual(Pose._md5sum, '863b248d5016ca62ea2e895ae5265cf9')
        self.assertEqual(Color._md5sum, '353891e354491c51aabe32df673fb446')
        self.assertEqual(Spawn._md5sum, '0b2d2e872a8e2887d5ed626f2bf2c561')
        self.assertEqual(Kill._md5sum, 'c1f3d28f1b044c871e6eff2e9fc3c667')
        self.assertEqual(SetPen._md5sum, '9f452acce566bf0c0954594f69a8e41b')
        self.assertEqual(TeleportAbsolute._md5sum, 'a130bc60ee6513855dc62ea83fcc5b20')
        self.assertEqual(TeleportRelative._md5sum, '9d5c2dcd348ac8f76ce2a4307bd63a13')

    def test_reset_log_lines_and_pose(self):
        start = self.rosout.count()
        self.reset()
        self.rosout.wait_for_line('INFO', 'Resetting turtlesim.', start)
        self.rosout.wait_for_line(
            'INFO', 'Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]', start)
        pose = self.pose.next_message()
        self.assertAlmostEqual(pose.x, 5.544445, places=5)
        self.assertAlmostEqual(pose.y, 5.544445, places=5)
        self.assertEqual((pose.theta, pose.linear_velocity, pose.angular_velocity), (0.0, 0.0, 0.0))

    # --- timing ---
    def test_a_pose_every_tick(self):
        start = self.pose.count()
        wait_until(lambda: self.pose.count() >= start + 190, 10.0, '190 poses')
        times = [arrival for arrival, _ in self.pose.entries(start)]
        rate = (len(times) - 1) / (times[-1] - times[0])
        self.assertAlmostEqual(rate, 1 / TICK_SECONDS, delta=0.02 / TICK_SECONDS)

    def test_one_command_moves_the_turtle_for_one_second(self):
        self.teleport(2.0, 5.0, 0.0)
        cmd_vel = connected_publisher('/turtle1/cmd_vel', Twist)
        wait_until(lambda: abs(self.pose.next_message().x - 2.0) < 1e-6, 5.0, 'the teleport')
        stopped = moved(lambda: cmd_vel.publish(twist(1.0)), self.pose)
        self.assertAlmostEqual(stopped.x - 2.0, ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.02)  # at 1 m/s
        self.assertAlmostEqual(stopped.y, 5.0, places=5)

    def test_teleport_shows_in_the_first_pose_after_the_reply(self):
        self.teleport(3.0, 4.0, 10.0)
        pose = self.pose.next_message()
        self.assertAlmostEqual(pose.x, 3.0, places=5)
        self.assertAlmostEqual(pose.y, 4.0, places=5)
        self.assertAlmostEqual(pose.theta, -2.566370, places=5)
        service('/turtle1/teleport_relative', TeleportRelative)(1.0, math.pi / 2)
        pose = self.pose.next_message()
        self.assertAlmostEqual(pose.x, 3.0 + math.cos(-2.566370 + math.pi / 2), places=5)
        self.assertAlmostEqual(pose.y, 4.0 + math.sin(-2.566370 + math.pi / 2), places=5)

    def test_who_called_a_service_first_is_told_on_service_calls(self):
        self.teleport(3.0, 4.0, 0.0)   # and setUp called /reset
        calls = TopicRecorder('/turtlesim/service_calls', String)
        try:
            told = calls.wait_for(lambda message: '/turtle1/teleport_absolute' in message.data, 10,
                                  'the teleport on /turtlesim/service_calls')
        finally:
            calls.close()
        self.assertIn(('/reset', rospy.get_name()), parse(told.data))
        self.assertIn(('/turtle1/teleport_absolute', rospy.get_name()), parse(told.data))
        self.assertEqual(told._connection_header['callerid'], '/turtlesim')

    # --- log texts and errors ---
    def test_wall_warning_and_silent_top_clamp(self):
        start = self.rosout.count()
        self.teleport(12.0, 3.0, 0.0)
        self.rosout.wait_for_line('WARN', 'Oh no! I hit the wall! (Clamping from [x=12.000000, y=8.088889])', start)
        self.assertAlmostEqual(self.pose.next_message().x, WORLD_SIZE, places=5)
        start = self.rosout.count()
        self.teleport(3.0, 12.0, 0.0)
        pose = self.pose.next_message()
        self.assertAlmostEqual(pose.y, WORLD_SIZE, places=5)
        self.clear()  # a later line, to know rosout has caught up
        self.rosout.wait_for_line('INFO', 'Clearing turtlesim.', start)
        self.assertNotIn('WARN', [level for level, _ in self.rosout.lines(start=start)])

    def test_spawn_kill_names_and_errors(self):
        self.assertEqual(self.spawn(1.0, 2.0, 0.5, '').name, 'turtle2')
        self.assertEqual(self.spawn(8.0, 2.0, 0.5, 'leo').name, 'leo')
        wait_until(lambda: '/leo/pose' in published_topics(), 5.0, '/leo/pose')
        self.assert_service_error(lambda: self.spawn(1.0, 1.0, 0.0, 'leo'), 'A turtled named [leo] already exists')
        for bad_name in ('1abc', 'foo bar', 'with-dash'):
            self.assert_service_error(lambda: self.spawn(1.0, 1.0, 0.0, bad_name),
                                      'Invalid turtle name [%s]' % bad_name)
        self.assert_service_error(lambda: self.kill('nemo'), 'Tried to kill turtle [nemo], which does not exist')
        self.kill('leo')
        wait_until(lambda: '/leo/pose' not in published_topics(), 5.0, '/leo/pose to disappear')
        self.assertNotIn('/leo/set_pen', graph()[2])
        self.assertEqual(self.spawn(1.0, 2.0, 0.5, '').name, 'turtle3')
        self.reset()
        self.assertEqual(self.spawn(1.0, 2.0, 0.5, '').name, 'turtle2')
        self.assertNotIn('/turtle3/pose', published_topics())

    def test_names_with_namespaces(self):
        self.spawn(1.0, 1.0, 0.0, 'a/b')
        self.spawn(2.0, 1.0, 0.0, '~priv')
        topics = published_topics()
        self.assertEqual(topics['/a/b/pose'], 'turtlesim/Pose')
        self.assertEqual(topics['/turtlesim/priv/pose'], 'turtlesim/Pose')
        self.assert_service_error(lambda: self.spawn(1.0, 1.0, 0.0, '/a/b'), 'A turtled named [/a/b] already exists')

    def test_non_finite_numbers_are_rejected(self):
        self.assert_service_error(lambda: self.spawn(NAN, 1.0, 0.0, 'nan_turtle'), 'x=nan must be a finite number')
        self.assert_service_error(lambda: self.teleport(1.0, float('inf'), 0.0), 'y=inf must be a finite number')
        cmd_vel = connected_publisher('/turtle1/cmd_vel', Twist)
        start = self.rosout.count()
        cmd_vel.publish(twist(NAN, 1.0))
        self.rosout.wait_for_line(
            'WARN', 'Ignoring a velocity command for [turtle1]: linear.x=nan must be a finite number', start)
        cmd_vel.publish(twist(1e308, 1e300, -1e308))
        wait_until(lambda: self.pose.next_message().linear_velocity > 1e38, 5.0, 'the huge command')
        for pose in self.pose.messages(self.pose.count() - 20):
            values = (pose.x, pose.y, pose.theta, pose.linear_velocity, pose.angular_velocity)
            self.assertTrue(all(math.isfinite(value) for value in values), pose)
            self.assertTrue(0.0 <= pose.x <= WORLD_SIZE + 1e-6 and 0.0 <= pose.y <= WORLD_SIZE + 1e-6, pose)
        self.assertNotIn('/nan_turtle/pose', published_topics())  # the rejected spawn made no turtle

    # --- pen, colour sensor, background ---
    def test_pen_and_colour_sensor(self):
        colour = TopicRecorder('/turtle1/color_sensor', Color)
        self.assertEqual(tuple(colour.next_message().__getstate__()), BACKGROUND)
        service('/turtle1/set_pen', SetPen)(255, 0, 0, 4, 0)
        cmd_vel = connected_publisher('/turtle1/cmd_vel', Twist)
        moved(lambda: cmd_vel.publish(twist(1.0)), self.pose)
        self.assertEqual(tuple(colour.next_message().__getstate__()), (255, 0, 0))
        colour.close()

    def test_background_params_are_read_only_when_clearing(self):
        colour = TopicRecorder('/turtle1/color_sensor', Color)
        try:
            for channel, value in zip('rgb', (10, 200, 30)):
                rospy.set_param('/turtlesim/background_' + channel, value)
            for _ in range(10):
                self.assertEqual(tuple(colour.next_message().__getstate__()), BACKGROUND)
            self.clear()
            self.assertEqual(tuple(colour.next_message().__getstate__()), (10, 200, 30))
            rospy.set_param('/turtlesim/background_g', 'green')
            start = self.rosout.count()
            self.clear()
            self.rosout.wait_for_line('WARN', "Parameter /turtlesim/background_g must be an integer from 0 to 255, "
                                      "not 'green': using 86", start)
            self.assertEqual(tuple(colour.next_message().__getstate__()), (10, 86, 30))
        finally:
            for channel, value in zip('rgb', BACKGROUND):
                rospy.set_param('/turtlesim/background_' + channel, value)
            colour.close()

    # --- pictures ---
    def test_save_canvas_writes_what_the_window_shows(self):
        save = service('/turtlesim/save_canvas', Trigger)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, 'sub', 'canvas.png')
            rospy.set_param('/turtlesim/canvas_png', path)
            service('/turtle1/set_pen', SetPen)(0, 255, 0, 5, 0)
            self.teleport(1.0, 1.0, 0.0)
            result = save()
            self.assertEqual((result.success, result.message), (True, path))
            with PilImage.open(path) as png:
                self.assertEqual((png.size, png.mode), ((500, 500), 'RGB'))
                picture = png.load()
            self.assertEqual(picture[490, 10], BACKGROUND)
            # the green teleport line from the centre (249.5, 249.5) to (45, 454)
            for fraction in (0.2, 0.5, 0.8):
                self.assertEqual(picture[round(249.5 - fraction * 204.5), round(249.5 + fraction * 204.5)],
                                 (0, 255, 0))
            # the turtle's icon is in the picture (not the pen colour, not the background)
            self.assertTrue(any(picture[45 + dx, 454] not in ((0, 255, 0), BACKGROUND) for dx in range(-8, 9)))
            rospy.set_param('/turtlesim/canvas_png', '/proc/no/such/dir/canvas.png')
            result = save()
            self.assertFalse(result.success)
            self.assertIn('Cannot save the canvas to /proc/no/such/dir/canvas.png', result.message)
            rospy.delete_param('/turtlesim/canvas_png')

    def test_canvas_topic_is_an_rgb8_picture_at_1_hz(self):
        canvas = TopicRecorder('/turtlesim/canvas', Image)
        wait_until(lambda: canvas.count() >= 3, 10.0, 'three canvas images')
        image = canvas.latest()
        self.assertEqual((image.width, image.height, image.encoding, image.step), (500, 500, 'rgb8', 1500))
        self.assertEqual(tuple(image.data[:3]), BACKGROUND)
        self.assertEqual(len(image.data), 500 * 500 * 3)
        second, third = canvas.entries()[1][0], canvas.entries()[2][0]
        self.assertAlmostEqual(third - second, 1.0, delta=0.25)
        canvas.close()


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'interface', TurtlesimInterfaceTest)
