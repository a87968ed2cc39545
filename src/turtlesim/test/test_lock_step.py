#!/usr/bin/env python3
"""turtlesim in lock step at 5x: while no node answers the poses with a velocity command, its
clock runs no faster than real time; a node that answers each pose it hears lets it run faster.
Started as the grader starts it (lock_step.test): the settings of its command line, not the
parameters that say otherwise."""
import os
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window
from turtlesim.msg import Pose
from turtlesim_testing import connected_publisher


class Responder:
    """Answers each pose of turtle1 with a still command while `answering`."""

    def __init__(self):
        self.answering = False
        self.cmd_vel = connected_publisher('/turtle1/cmd_vel', Twist)
        rospy.Subscriber('/turtle1/pose', Pose, self.on_pose, queue_size=1)

    def on_pose(self, _pose):
        if self.answering:
            self.cmd_vel.publish(Twist())


class LockStepTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('turtlesim_lock_step_test')
        cls.clock = TopicRecorder('/clock', Clock)
        cls.responder = Responder()
        cls.clock.next_message(30.0)

    def tearDown(self):
        self.responder.answering = False

    def factor_over(self, seconds):
        start_wall, start_sim = time.monotonic(), self.clock.latest().clock.to_sec()
        end_wall = measurement_window(seconds, start_wall)
        return (self.clock.latest().clock.to_sec() - start_sim) / (end_wall - start_wall)

    def test_with_no_answer_the_clock_runs_no_faster_than_real_time(self):
        self.assertLess(self.factor_over(2.0), 1.05)

    def test_answers_let_the_clock_run_faster_than_real_time(self):
        self.responder.answering = True
        self.factor_over(0.5)   # the answers under way
        self.assertGreater(self.factor_over(2.0), 2.0)

    def test_the_canvas_is_saved_where_the_command_line_says(self):
        saved = rospy.ServiceProxy('/turtlesim/save_canvas', Trigger)()
        self.addCleanup(lambda: os.path.exists(saved.message) and os.remove(saved.message))
        self.assertTrue(saved.success, saved.message)
        self.assertEqual(os.path.basename(saved.message), 'lock_step_canvas.png')
        self.assertTrue(os.path.isfile(saved.message))
        self.assertFalse(os.path.exists(os.path.join(os.path.dirname(saved.message), 'elsewhere.png')))


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'lock_step', LockStepTest)
