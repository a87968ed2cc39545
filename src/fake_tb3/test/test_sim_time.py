#!/usr/bin/env python3
"""rostest: fake_tb3 on simulated time at 10x in the wall_ahead world: /clock, rates in simulated
time, exact ranges, a collision, bad input, pictures."""
import math
import os
import shutil
import tempfile
import time
import unittest

import numpy as np
import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from PIL import Image
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState, LaserScan
from std_msgs.msg import String, UInt32
from std_srvs.srv import Trigger

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window, wait_until
from fake_tb3_testing import rosout_lines, stamp_rate

REAL_TIME_FACTOR = 10.0
# The body's front is 0.038 m ahead of base_footprint (burger box 0.14 m centred at -0.032).
FRONT = 0.038


class SimTimeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('sim_time_test')
        cls.clock = TopicRecorder('/clock', Clock)
        cls.odom = TopicRecorder('/odom', Odometry)
        cls.joint_states = TopicRecorder('/joint_states', JointState)
        cls.scan = TopicRecorder('/scan', LaserScan)
        cls.collisions = TopicRecorder('/collisions', UInt32)
        cls.rosout = TopicRecorder('/rosout', Log)
        cls.cmd_vel = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
        wait_until(lambda: cls.scan.latest() and cls.odom.latest() and cls.collisions.latest()
                   and cls.clock.latest(), 30, 'scan, odom, collisions and clock')
        wait_until(lambda: cls.cmd_vel.get_num_connections(), 10, 'fake_tb3 on /cmd_vel')

    def drive(self, linear, angular=0.0):
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        self.cmd_vel.publish(twist)

    def stopped_away_from_the_wall(self):
        """Whatever the tests before left (the robot pushing on the wall, backing off): stopped, the
        wall 1 m or more ahead."""
        self.drive(-0.5)
        wait_until(lambda: self.odom.latest().pose.pose.position.x <= 1.0, 30, 'backing away from the wall')
        self.drive(0.0)
        wait_until(lambda: self.odom.latest().twist.twist.linear.x == 0.0, 10, 'the robot stopped')

    def test_scan_sees_the_wall_exactly(self):
        # Laser 0.032 m behind base_footprint at the origin, wall face at x = 2.0: the first scan,
        # from the spawn pose, before any test drove.
        scan = self.scan.messages()[0]
        self.assertAlmostEqual(scan.ranges[0], 2.032, places=5)
        self.assertAlmostEqual(scan.ranges[30], 2.032 / math.cos(30 * scan.angle_increment),
                               places=4)
        self.assertEqual(scan.ranges[180], math.inf)

    def test_clock_runs_at_the_real_time_factor(self):
        start_wall = time.monotonic()
        start_clock = self.clock.latest().clock
        end_wall = measurement_window(4.0, start_wall)
        simulated = (self.clock.latest().clock - start_clock).to_sec()
        factor = simulated / (end_wall - start_wall)
        self.assertAlmostEqual(factor, REAL_TIME_FACTOR, delta=0.15 * REAL_TIME_FACTOR)

    def test_rates_in_simulated_time(self):
        start = self.clock.latest().clock + rospy.Duration(1)
        end = start + rospy.Duration(10)
        wait_until(lambda: self.odom.latest().header.stamp > end + rospy.Duration(0.5), 30,
                   '11.5 simulated seconds')
        self.assertAlmostEqual(stamp_rate(self.scan, start, end), 5.0, delta=0.1)
        self.assertAlmostEqual(stamp_rate(self.odom, start, end), 30.0, delta=0.3)
        self.assertAlmostEqual(stamp_rate(self.joint_states, start, end), 30.0, delta=0.3)

    def test_drives_into_the_wall_and_stops_at_the_contact(self):
        self.stopped_away_from_the_wall()
        self.drive(1.0)
        wait_until(lambda: self.collisions.latest().data == 1, 30, 'a collision')
        wait_until(lambda: self.odom.latest().twist.twist.linear.x == 0.0, 5, 'the robot stopped')
        self.assertAlmostEqual(self.odom.latest().pose.pose.position.x, 2.0 - FRONT, delta=0.001)
        warnings = wait_until(lambda: rosout_lines(self.rosout, 'collision at x 1.96'), 5,
                              'the collision warning')
        self.assertIn('the body touches an obstacle (collision 1)', warnings[0])
        # Pushing on is the same contact: no new collision, no motion.
        stamp = self.odom.latest().header.stamp
        wait_until(lambda: self.odom.latest().header.stamp > stamp + rospy.Duration(2), 10, '2 s')
        self.assertEqual(self.collisions.latest().data, 1)
        self.assertAlmostEqual(self.odom.latest().pose.pose.position.x, 2.0 - FRONT, delta=0.001)
        # The scan from there: the wall 0.07 m ahead of the laser is inside range_min: not seen.
        wait_until(lambda: self.scan.latest().header.stamp > stamp + rospy.Duration(2), 10,
                   'a scan')
        self.assertEqual(self.scan.latest().ranges[0], math.inf)

    def test_non_finite_commands_are_refused_and_the_last_one_holds(self):
        self.stopped_away_from_the_wall()
        self.drive(-0.5)
        wait_until(lambda: self.odom.latest().twist.twist.linear.x == -0.5, 10, 'backing off')
        wheels = wait_until(lambda: self.joint_states.latest().velocity[0] < 0
                            and self.joint_states.latest(), 10, 'the wheels turning back')
        self.assertEqual(list(wheels.velocity), [-0.5 / 0.033] * 2)  # rad/s on 0.033 m wheels
        self.drive(float('nan'))
        self.drive(0.1, float('inf'))
        wait_until(lambda: rosout_lines(self.rosout, 'non-finite velocity'), 10, 'a warning')
        self.assertEqual(self.odom.latest().twist.twist.linear.x, -0.5)
        self.drive(0.0)

    def test_save_picture_where_the_parameter_said_at_start_up(self):
        self.stopped_away_from_the_wall()
        path = rospy.get_param('/fake_tb3/picture_png')   # a new folder's (sim_time.test)
        os.makedirs(os.path.dirname(path))
        self.addCleanup(shutil.rmtree, os.path.dirname(path))   # the picture at shutdown has nowhere to go
        save = rospy.ServiceProxy('/fake_tb3/save_picture', Trigger)
        save.wait_for_service(10)
        reply = save()
        self.assertTrue(reply.success)
        self.assertEqual(reply.message, path)
        image = np.asarray(Image.open(path).convert('RGB'))
        red = np.all(image == (230, 20, 20), axis=2).sum()
        self.assertGreater(red, 50)  # the scan's dots on the wall
        # Set later, the parameter changes nothing: fake_tb3 writes where it was told at start-up.
        elsewhere = os.path.join(tempfile.mkdtemp(), 'elsewhere.png')
        rospy.set_param('/fake_tb3/picture_png', elsewhere)
        self.assertEqual(save().message, path)
        self.assertFalse(os.path.exists(elsewhere))
        os.rmdir(os.path.dirname(elsewhere))
        os.remove(path)
        os.mkdir(path)   # a folder where the picture goes: it cannot be written
        reply = save()
        self.assertFalse(reply.success)
        self.assertIn('cannot write', reply.message)
        # Who called the service, as fake_tb3 tells it.
        calls = TopicRecorder('/fake_tb3/service_calls', String)
        try:
            told = calls.wait_for(lambda message: message.data, 10, 'fake_tb3 to tell who called')
        finally:
            calls.close()
        self.assertEqual(told.data, '/fake_tb3/save_picture %s' % rospy.get_name())


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'sim_time', SimTimeTest)
