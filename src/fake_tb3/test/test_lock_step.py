#!/usr/bin/env python3
"""rostest: fake_tb3 with ~lock_step in the wall_ahead world (no noise): a node that answers each
scan as avoid_obstacle.py does (0.5 m/s while the front beam reads more than 0.5 m, else 0), its
first answer kept back 50 ms as a busy machine keeps a node from the processor, stops the robot at
the same place at any real-time factor and with a core kept busy beside it; while no node answers,
the clock runs no faster than real time."""
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window, wait_until
from course_testing.processes import busy_core

# The wall's face is at x = 2.0 and the laser 0.032 m behind base_footprint: the front beam reads
# 2.032 - x. Answered at once, every scan finds the robot 0.1 m (0.5 m/s for a scan period of
# 0.2 s) farther than the one before, from x = 0: the first scan within 0.5 m is at 2.032 - 1.6.
STOP_X = 1.6
SPEED = 0.5
# Wall seconds the first answer is kept back: without lock step, 0.1 m of drive missing at 2x
# (0.5 m at 10x), which the stop does not make up.
FIRST_ANSWER_DELAY = 0.05


class Responder:
    """avoid_obstacle.py's rule, answering each scan while `answering`."""

    def __init__(self):
        self.answering = False
        self.answered = 0
        self.cmd_vel = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        rospy.Subscriber('/scan', LaserScan, self.on_scan)

    def on_scan(self, scan):
        if self.answering:
            if not self.answered:
                time.sleep(FIRST_ANSWER_DELAY)   # the node's slow reaction that lock step waits for
            self.answered += 1
            move = Twist()
            move.linear.x = SPEED if scan.ranges[0] > 0.5 else 0.0
            self.cmd_vel.publish(move)


class LockStepTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('lock_step_test')
        cls.clock = TopicRecorder('/clock', Clock)
        cls.odom = TopicRecorder('/odom', Odometry)
        cls.responder = Responder()
        wait_until(lambda: cls.odom.latest() and cls.clock.latest() and cls.responder.cmd_vel.get_num_connections(),
                   30, 'fake_tb3 on odom, clock and cmd_vel')

    def tearDown(self):
        self.responder.answering = False

    def test_answered_scans_stop_the_robot_at_the_same_place(self):
        with busy_core(rospy.get_param('~busy_core')):
            self.responder.answering = True
            wait_until(lambda: self.odom.latest().twist.twist.linear.x > 0, 30, 'the robot driving')
            wait_until(lambda: self.odom.latest().twist.twist.linear.x == 0, 60, 'the robot stopped')
        self.assertAlmostEqual(self.odom.latest().pose.pose.position.x, STOP_X, delta=0.001)

    def test_unanswered_scans_let_the_clock_run_no_faster_than_real_time(self):
        start_wall, start_sim = time.monotonic(), self.clock.latest().clock.to_sec()
        end_wall = measurement_window(4.0, start_wall)
        self.assertLessEqual((self.clock.latest().clock.to_sec() - start_sim) / (end_wall - start_wall), 1.0)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'lock_step', LockStepTest)
