#!/usr/bin/env python3
"""rostest: fake_tb3 in turtlebot3_world on real time: rates, message contents, frames, TF; and a
second simulator (namespace limited, a waffle) with cmd_vel_timeout 0.5 s and clamp_speed."""
import math
import time
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, LaserScan

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window, wait_until
from fake_tb3_testing import lookup

WINDOW = 8.0  # wall seconds over which rates are measured


class RealTimeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('real_time_test')
        cls.odom = TopicRecorder('/odom', Odometry)
        cls.joint_states = TopicRecorder('/joint_states', JointState)
        cls.scan = TopicRecorder('/scan', LaserScan)
        cls.imu = TopicRecorder('/imu', Imu)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        # Each recorder's first message: the topics connect one by one (joint_states had none yet
        # when its test began, in a run of the suite under strace, 2026-12-05).
        recorders = (cls.scan, cls.odom, cls.joint_states, cls.imu)
        wait_until(lambda: all(recorder.latest() for recorder in recorders), 30, 'scan, odom, joint_states and imu')

    def test_rates(self):
        start = time.monotonic()
        end = measurement_window(WINDOW, start)
        for recorder, expected in ((self.scan, 5.0), (self.odom, 30.0), (self.joint_states, 30.0),
                                   (self.imu, 30.0)):
            rate = recorder.rate(start, end)
            self.assertAlmostEqual(rate, expected, delta=0.03 * expected,
                                   msg='%s at %.3f Hz' % (recorder.subscriber.name, rate))
        # Stamps follow the wall clock on real time.
        stamp = self.odom.latest().header.stamp
        self.assertAlmostEqual(stamp.to_sec(), time.time(), delta=0.5)

    def test_scan_message(self):
        scan = self.scan.latest()
        self.assertEqual(scan.header.frame_id, 'base_scan')
        self.assertEqual(len(scan.ranges), 360)
        self.assertEqual(len(scan.intensities), 360)
        self.assertEqual(scan.angle_min, 0.0)
        self.assertAlmostEqual(scan.angle_max, 6.28319, places=5)
        self.assertAlmostEqual(scan.angle_increment, 6.28319 / 359, places=6)
        self.assertAlmostEqual(scan.range_min, 0.12, places=6)
        self.assertAlmostEqual(scan.range_max, 3.5, places=6)
        self.assertEqual((scan.time_increment, scan.scan_time), (0.0, 0.0))
        # At the spawn pose, beam 180 meets the wall 0.609 m away (see test/unit/test_lidar.py),
        # with noise of stddev 0.01; beam 0 sees nothing within 3.5 m.
        self.assertAlmostEqual(scan.ranges[180], 0.609, delta=0.05)
        self.assertEqual(scan.ranges[0], math.inf)
        finite = [r for r in scan.ranges if math.isfinite(r)]
        self.assertTrue(finite and min(finite) >= 0.12 and max(finite) <= 3.5)

    def test_odometry_and_tf_at_the_spawn_pose(self):
        odom = self.odom.latest()
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ('odom', 'base_footprint'))
        pose = odom.pose.pose
        self.assertEqual((pose.position.x, pose.position.y), (-2.0, -0.5))
        self.assertEqual(pose.orientation.w, 1.0)
        diagonal = [odom.pose.covariance[i * 7] for i in range(6)]
        self.assertEqual(diagonal, [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3])
        transform = wait_until(lambda: lookup(self.tf_buffer, 'odom', 'base_footprint'), 10,
                               'the odom TF')
        self.assertEqual((transform.translation.x, transform.translation.y), (-2.0, -0.5))

    def test_speed_clamp_and_command_timeout(self):
        limited = TopicRecorder('/limited/odom', Odometry)
        publisher = rospy.Publisher('/limited/cmd_vel', Twist, queue_size=1)
        wait_until(publisher.get_num_connections, 20, 'the limited simulator on cmd_vel')
        twist = Twist()
        twist.linear.x, twist.angular.z = 1.0, -5.0
        sent = time.monotonic()
        publisher.publish(twist)
        moving = wait_until(lambda: limited.latest() and limited.latest().twist.twist.linear.x
                            and limited.latest().twist.twist, 10, 'the waffle to move')
        self.assertEqual((moving.linear.x, moving.angular.z), (0.26, -1.82))  # waffle limits
        wait_until(lambda: limited.latest().twist.twist.linear.x == 0.0, 10, 'the timeout stop')
        self.assertAlmostEqual(time.monotonic() - sent, 0.5, delta=0.25)
        limited.subscriber.unregister()

    def test_joint_states_and_imu(self):
        joints = self.joint_states.latest()
        self.assertEqual(joints.name, ['wheel_left_joint', 'wheel_right_joint'])
        self.assertEqual(len(joints.position), 2)
        imu = self.imu.latest()
        self.assertEqual(imu.header.frame_id, 'imu_link')
        self.assertAlmostEqual(imu.linear_acceleration.z, 9.80665)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'real_time', RealTimeTest)
