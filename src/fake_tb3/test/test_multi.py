#!/usr/bin/env python3
"""rostest: multi_turtlebot3: three robots in namespaces with prefixed frames, driven separately."""
import math
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from fake_tb3_testing import lookup

SPAWNS = {'tb3_0': (-7.0, -1.0, 1.57), 'tb3_1': (7.0, -1.0, 1.57), 'tb3_2': (0.5, 3.0, 0.0)}


def yaw_of(orientation):
    return 2 * math.atan2(orientation.z, orientation.w)


class MultiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('multi_test')
        cls.odom = {name: TopicRecorder('/%s/odom' % name, Odometry) for name in SPAWNS}
        cls.scan = {name: TopicRecorder('/%s/scan' % name, LaserScan) for name in SPAWNS}
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        recorders = list(cls.odom.values()) + list(cls.scan.values())
        wait_until(lambda: all(r.latest() for r in recorders), 30, 'odom and scan of every robot')

    def test_namespaces_frames_and_spawn_poses(self):
        for name, (x, y, yaw) in SPAWNS.items():
            odom = self.odom[name].messages()[0]  # from before any test drove
            self.assertEqual(odom.header.frame_id, name + '/odom')
            self.assertEqual(odom.child_frame_id, name + '/base_footprint')
            self.assertEqual((odom.pose.pose.position.x, odom.pose.pose.position.y), (x, y))
            self.assertAlmostEqual(yaw_of(odom.pose.pose.orientation), yaw, places=9)
            self.assertEqual(self.scan[name].latest().header.frame_id, name + '/base_scan')

    def test_robot_state_publishers_complete_each_tree(self):
        # base_scan is 0.032 m behind base_footprint and 0.010 + 0.172 m up (burger).
        x, y, yaw = SPAWNS['tb3_2']
        laser = wait_until(lambda: lookup(self.tf_buffer, 'tb3_2/odom', 'tb3_2/base_scan'), 20,
                           'the TF tb3_2/odom -> tb3_2/base_scan')
        self.assertAlmostEqual(laser.translation.x, x - 0.032 * math.cos(yaw), places=6)
        self.assertAlmostEqual(laser.translation.y, y - 0.032 * math.sin(yaw), places=6)
        self.assertAlmostEqual(laser.translation.z, 0.182, places=6)

    def test_each_robot_obeys_its_own_cmd_vel(self):
        publisher = rospy.Publisher('/tb3_1/cmd_vel', Twist, queue_size=1)
        wait_until(publisher.get_num_connections, 10, 'fake_tb3 on /tb3_1/cmd_vel')
        self.addCleanup(publisher.publish, Twist())
        start_y = self.odom['tb3_1'].latest().pose.pose.position.y
        twist = Twist()
        twist.linear.x = 0.5
        publisher.publish(twist)
        # tb3_1 faces +y (yaw 1.57): it drives up; the others stay.
        wait_until(lambda: self.odom['tb3_1'].latest().pose.pose.position.y > start_y + 1.0, 30,
                   'tb3_1 to drive 1 m')
        for name in ('tb3_0', 'tb3_2'):
            position = self.odom[name].latest().pose.pose.position
            self.assertEqual((position.x, position.y), SPAWNS[name][:2])


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'multi', MultiTest)
