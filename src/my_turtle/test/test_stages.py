#!/usr/bin/env python3
"""The three stages of the slides, each run as a student runs it, measured from turtle1's poses."""
import math
import re
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

from course_checks import turtle
from course_checks.turtle import POSE_RATE_HZ, duration, tick_speeds, travelled
from course_common.waiting import wait_until
from my_turtle_testing import POSE_LINE, PrintingNode, turtle1_poses

FORWARD_SPEED_MPS = 0.5
SPEED_TOLERANCE = 0.02  # relative
POSITION_TOLERANCE = 0.011  # metres: a printed x or y (2 decimals) against the pose turtlesim published
START = 5.544445  # turtle1 spawns in the middle of the 11.09 m square
WINDOW_S = 1.0  # about 62 poses: their median tick step is exact (turtlesim moves a turtle by a fixed TICK_SECONDS a tick)


class StagesTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('stages_test')
        cls.poses = turtle1_poses()
        cls.teleop = rospy.Publisher('/cmd_vel_mux/input/teleop', Twist, queue_size=1)

    def setUp(self):
        rospy.wait_for_service('/reset', 30)
        rospy.ServiceProxy('/reset', Empty)()
        self.poses.wait_for(lambda pose: pose.linear_velocity == 0 and abs(pose.x - START) < 1e-4,
                            5, 'turtle1 back in the middle, still, after /reset')
        self.node = None

    def tearDown(self):
        if self.node is not None:
            self.assertEqual(self.node.stop(), 0, 'the node did not exit cleanly on Ctrl-C')

    def start(self, executable, first_line):
        self.node = PrintingNode('my_turtle', executable)
        self.node.wait_for_line(first_line, 30)

    def check_forward_at_half_a_metre_per_second(self):
        self.poses.wait_for(lambda pose: pose.linear_velocity > 0, 5, 'the turtle to start moving')
        samples = self.poses.record(WINDOW_S)
        first, last = samples[0][1], samples[-1][1]
        speed, _ = tick_speeds(samples)
        rospy.loginfo('measured %.4f m/s over %d poses', speed, len(samples))
        self.assertGreater(last.x, first.x, 'the turtle does not move along +x')
        self.assertAlmostEqual(speed, FORWARD_SPEED_MPS, delta=FORWARD_SPEED_MPS * SPEED_TOLERANCE)
        self.assertAlmostEqual(last.y, START, places=4, msg='the turtle left the x axis')
        self.assertAlmostEqual(last.theta, 0.0, places=4, msg='the turtle turned')

    def check_pose_lines(self):
        """Every pose arrives as one line in the slide's format, with the turtle's coordinates."""
        samples = self.poses.record(1.0)
        lines = [line for line in self.node.lines if re.match(POSE_LINE, line)]
        self.assertGreater(len(lines), 0, 'no pose line in the output: %s' % self.node.lines[-5:])
        printed = [tuple(float(value) for value in re.match(POSE_LINE, line).groups())
                   for line in lines]
        for x, y in printed[-10:]:
            self.assertAlmostEqual(y, round(START, 2))
            self.assertTrue(START - 0.01 <= x <= samples[-1][1].x + 0.1, 'x %.2f is off the path' % x)
        self.assertEqual(printed[-10:], sorted(printed[-10:]), 'the printed x does not grow')
        # The node prints at the rate poses arrive: count the lines of a one-second window.
        before = len(lines)
        window = self.poses.record(1.0)
        count = sum(1 for line in self.node.lines if re.match(POSE_LINE, line)) - before
        self.assertAlmostEqual(count / duration(window), POSE_RATE_HZ, delta=POSE_RATE_HZ * 0.2)

    def test_stage1_forward(self):
        self.start('my_turtle_forward', 'Starting to move forward')
        self.check_forward_at_half_a_metre_per_second()
        self.assertFalse(any(re.match(POSE_LINE, line) for line in self.node.lines),
                         'stage 1 does not print poses')

    def test_stage2_forward_printing_the_pose(self):
        self.start('my_turtle_pose', 'Starting to move forward')
        self.check_forward_at_half_a_metre_per_second()
        self.check_pose_lines()

    def test_stage3_follows_the_teleop(self):
        self.start('my_turtle_node', 'Waiting for teleop commands on cmd_vel_mux/input/teleop')
        still = self.poses.record(1.0)
        self.assertEqual(travelled(still), 0.0, 'the turtle moved before any teleop command')
        self.assertTrue(re.match(POSE_LINE, self.node.lines[-1]), 'no pose lines while still')

        self.send(0.3, 0.6)
        self.poses.wait_for(lambda pose: pose.angular_velocity > 0.5, 5, 'the turtle to follow')
        followed = turtle.drives_at(self.poses.record(WINDOW_S), 0.3, 0.6, SPEED_TOLERANCE)   # as the grader judges it
        self.assertTrue(followed.passed, followed.reason)

        self.send(0.0, 0.0)
        self.poses.wait_for(lambda pose: pose.linear_velocity == 0 and pose.angular_velocity == 0,
                            5, 'the turtle to stop on a zero command')
        stopped = self.poses.record(1.0)
        self.assertEqual(travelled(stopped), 0.0, 'the turtle still moves after a zero command')
        self.assertTrue(math.isclose(stopped[0][1].theta, stopped[-1][1].theta))
        # The last pose printed is where the turtle stands, as the grader judges it.
        final = stopped[-1][1]

        def printed():
            lines = [re.match(POSE_LINE, line) for line in self.node.lines[-20:]]
            return turtle.printed_position([tuple(map(float, m.groups())) for m in lines if m], final,
                                           POSITION_TOLERANCE)
        wait_until(lambda: printed().passed, 5, 'the node to print where the turtle stands')

    def send(self, linear, angular):
        """One teleop command, as the keyboard teleop sends it (my_turtle_node keeps the last one)."""
        wait_until(lambda: self.teleop.get_num_connections() > 0, 10, 'my_turtle_node to subscribe')
        twist = Twist()
        twist.linear.x = linear
        twist.angular.z = angular
        self.teleop.publish(twist)


if __name__ == '__main__':
    rostest.rosrun('my_turtle', 'stages', StagesTest)
