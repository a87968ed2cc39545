#!/usr/bin/env python3
"""turtle_teleop_key through a pseudo-terminal, and mimic copying turtle1's motion onto turtle2."""
import math
import subprocess
import unittest

import rospy
import rostest

from course_testing.processes import PtyProgram
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import Spawn, TeleportAbsolute
from turtlesim.world import TICK_SECONDS
from turtlesim_testing import ONE_COMMAND_TICKS, moved, publishes_to, wait_until_still

UP, DOWN, RIGHT, LEFT = '\x1b[A', '\x1b[B', '\x1b[C', '\x1b[D'
TOLERANCE = 0.05  # one tick at 2 m/s is 0.032 m


class TeleopAndMimicTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('turtlesim_programs_test')
        rospy.wait_for_service('/spawn', 10.0)
        rospy.ServiceProxy('/spawn', Spawn)(2.0, 2.0, 0.0, 'turtle2')
        cls.turtle1 = TopicRecorder('/turtle1/pose', Pose)
        cls.turtle2 = TopicRecorder('/turtle2/pose', Pose)

    def start_teleop(self):
        teleop = PtyProgram(['rosrun', 'turtlesim', 'turtle_teleop_key'])
        self.addCleanup(teleop.stop)
        teleop.wait_for_output("Use arrow keys to move the turtle. 'q' to quit.", 15.0)
        wait_until(lambda: publishes_to('/teleop_turtle', '/turtle1/cmd_vel', '/turtlesim'), 10.0,
                   'turtlesim to connect to the teleop')
        return teleop

    def press(self, teleop, key):
        """Press a key; return turtle1's and turtle2's poses before and after the motion it causes."""
        before = (wait_until_still(self.turtle1), wait_until_still(self.turtle2))
        after = (moved(lambda: teleop.type(key), self.turtle1), wait_until_still(self.turtle2))
        return before, after

    def test_arrow_keys_drive_turtle1_and_mimic_copies_them(self):
        rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(3.0, 5.0, 0.0)
        teleop = self.start_teleop()
        self.assertIn('Reading from keyboard', teleop.output)

        (t1, t2), (t1_after, t2_after) = self.press(teleop, UP)
        self.assertAlmostEqual(t1_after.x - t1.x, 2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=TOLERANCE)
        self.assertAlmostEqual(t1_after.y, t1.y, places=4)
        # mimic lags a tick or two
        self.assertAlmostEqual(t2_after.x - t2.x, 2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.15)

        (t1, t2), (t1_after, t2_after) = self.press(teleop, LEFT)
        self.assertAlmostEqual(t1_after.theta - t1.theta, 2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.04)
        self.assertAlmostEqual(t2_after.theta - t2.theta, 2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.1)

        (t1, _), (t1_after, _) = self.press(teleop, RIGHT)
        self.assertAlmostEqual(t1_after.theta - t1.theta, -2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.04)

        (t1, t2), (t1_after, t2_after) = self.press(teleop, DOWN)
        self.assertAlmostEqual(t1_after.x - t1.x, -2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=TOLERANCE)
        # turtle1 backed up, but a pose carries speed only: turtle2 went forward along its heading
        forward = (t2_after.x - t2.x) * math.cos(t2.theta) + (t2_after.y - t2.y) * math.sin(t2.theta)
        self.assertAlmostEqual(forward, 2.0 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.15)

        teleop.type('x')  # not a key the teleop knows: nothing happens, it keeps running
        teleop.type('q')
        wait_until(lambda: teleop.process.poll() is not None, 10.0, 'the teleop to quit on q')
        self.assertEqual(teleop.process.returncode, 0)
        self.assertNotIn('Traceback', teleop.read_available())

    def test_scale_linear_is_read_from_the_node_namespace(self):
        rospy.set_param('/scale_linear', 0.5)
        self.addCleanup(rospy.delete_param, '/scale_linear')
        teleop = self.start_teleop()
        (t1, _), (t1_after, _) = self.press(teleop, UP)
        distance = math.hypot(t1_after.x - t1.x, t1_after.y - t1.y)
        self.assertAlmostEqual(distance, 0.5 * ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.02)

    def test_teleop_without_a_terminal_says_so_and_fails(self):
        result = subprocess.run(['rosrun', 'turtlesim', 'turtle_teleop_key'], stdin=subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=30)
        self.assertNotEqual(result.returncode, 0)
        self.assertNotIn('Traceback', result.stderr + result.stdout)
        self.assertEqual(result.stderr.strip().count('\n'), 0, result.stderr)
        self.assertIn('standard input is not a terminal', result.stderr)


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'programs', TeleopAndMimicTest)
