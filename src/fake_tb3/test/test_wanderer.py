#!/usr/bin/env python3
"""rostest: the wanderer (turtlebot3_simulation) in turtlebot3_world for ~seconds simulated seconds
(private parameter, default 120): it moves and never collides."""
import unittest

import rosnode
import rospy
import rostest
from nav_msgs.msg import Odometry
from std_msgs.msg import UInt32

from course_checks.figures import path_length
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until


class WandererTest(unittest.TestCase):
    def test_wanders_without_a_collision(self):
        rospy.init_node('wanderer_test')
        seconds = rospy.get_param('~seconds', 120.0)
        odom = TopicRecorder('/odom', Odometry)
        collisions = TopicRecorder('/collisions', UInt32)
        wait_until(odom.latest, 30, 'odometry')
        start = odom.latest().header.stamp
        wait_until(lambda: odom.latest().header.stamp - start > rospy.Duration(seconds),
                   seconds * 2 + 30, '%g simulated seconds' % seconds)
        self.assertIn('/turtlebot3_drive', rosnode.get_node_names())
        self.assertEqual(rospy.get_param('/cmd_vel_topic_name'), '/cmd_vel')
        counts = [message.data for message in collisions.messages()]
        self.assertEqual(counts, [0])
        points = [(m.pose.pose.position.x, m.pose.pose.position.y) for m in odom.messages()]
        travelled = path_length(points)
        # 0.3 m/s when going forward; turns take 0.35 s each.
        self.assertGreater(travelled, 0.1 * seconds)
        rospy.loginfo('wanderer: %.1f m in %g simulated seconds, no collision', travelled, seconds)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'wanderer', WandererTest)
