#!/usr/bin/env python3
"""Exercises 2 and 3: the listener prints the pose the simulator publishes, and the circle node
drives turtle1, or the spawned turtle "robotics" of the report's Fig. 5, round a circle of radius
1 m while printing the pose."""
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist

from course_checks import turtle
from course_checks.turtle import turtle_poses
from course_common.waiting import wait_until
from ros_exercises_testing import Command

TURTLE1_START = (5.544445, 5.544445)
NUMBER = r'(-?\d+\.\d+)'
# Parameters exercise3.launch leaves alone, read by the turtlesim it starts.
SIMULATED_CLOCK = {'/use_sim_time': True, '/turtlesim/real_time_factor': 5.0, '/turtlesim/lock_step': True}


def assert_printed_poses_were_published(test, printed, recorder):
    """The printed (x, y, theta) are poses the simulator published, in order, keeping up with the turtle."""
    verdict = turtle.printed_poses_published(printed, recorder)
    test.assertTrue(verdict.passed, verdict.reason)


def assert_circle(test, recorder, centre, radius):
    """One full turn of moving poses lies on a circle of `radius` around `centre`, within 2 %."""
    wait_until(lambda: len(turtle.moving_points(turtle.pose_array(recorder))) >= turtle.full_turn(radius), 30,
               'a full turn of poses')
    verdict = turtle.circle(turtle.moving_points(turtle.pose_array(recorder)), centre, radius, 0.02)
    test.assertTrue(verdict.passed, verdict.reason)


class TestListenerCircle(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_listener_circle')

    def test_exercise2_listener_prints_the_pose(self):
        self.recorder = turtle_poses('turtle1')
        listener = Command('roslaunch', 'ros_exercises', 'exercise2.launch')
        try:
            line = r'x: %s, y: %s, theta: %s' % (NUMBER, NUMBER, NUMBER)
            self.assertEqual(listener.wait_for(line)[0], ('5.544445', '5.544445', '0.000000'))
            # Drive the turtle as a teleop would, until the listener has printed it moving.
            teleop = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
            command = Twist()
            command.linear.x, command.angular.z = 1.0, 0.5
            timer = rospy.Timer(rospy.Duration(0.05), lambda _: teleop.publish(command))
            try:
                wait_until(lambda: any(float(x) > 6.0 for x, _, _ in listener.matches(line)), 30,
                           'the listener printing the turtle beyond x = 6')
            finally:
                timer.shutdown()
            printed = listener.matches(line)
            assert_printed_poses_were_published(self, printed, self.recorder)
            self.assertGreater(len(set(printed)), 20, 'the printed pose hardly changed')
        finally:
            self.assertEqual(listener.stop(), 0)

    def tearDown(self):
        self.recorder.close()

    def drive_circle(self, turtle, centre, *launch_arguments):
        """Runs exercise3.launch and checks the circle of radius 1 m and the printed poses.
        turtlesim runs on its simulated clock at 5x, each tick waiting for the circle node's answer
        to the pose before (lock step, as the grader runs it): the same circle as at 1x, in a fifth
        of the time (nothing here measures time)."""
        for name, value in SIMULATED_CLOCK.items():
            rospy.set_param(name, value)
            self.addCleanup(rospy.delete_param, name)
        self.recorder = turtle_poses(turtle)
        circle = Command('roslaunch', 'ros_exercises', 'exercise3.launch', *launch_arguments)
        try:
            assert_circle(self, self.recorder, centre, 1.0)
            printed = circle.wait_for(r'Turtle subscriber@\[%s, %s, %s\]' % (NUMBER, NUMBER, NUMBER), count=100)
            assert_printed_poses_were_published(self, printed, self.recorder)
        finally:
            self.assertEqual(circle.stop(), 0)

    def test_exercise3_turtle1_circle_of_radius_1(self):
        self.drive_circle('turtle1', (TURTLE1_START[0], TURTLE1_START[1] + 1.0))

    def test_exercise3_report_variant_on_robotics(self):
        # exercise3.launch spawns "robotics" at (4, 2, 0): the centre is 1 m to its left.
        self.drive_circle('robotics', (4.0, 3.0), 'turtle:=robotics')


if __name__ == '__main__':
    rostest.rosrun('ros_exercises', 'test_listener_circle', TestListenerCircle)
