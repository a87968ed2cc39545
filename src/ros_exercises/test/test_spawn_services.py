#!/usr/bin/env python3
"""Exercise 4: the client spawns "robotics" where it is told (arguments or parameters), kills and
clears, and says clearly why it fails (taken name, unknown turtle, bad arguments), exiting non-zero.
Also exercise 5's node on bad input: bad parameters, and its turtle killed while it drives."""
import re
import unittest

import rospy
import rostest
from turtlesim.srv import Kill

from course_checks.turtle import at_pose, turtle_poses
from course_testing.processes import run
from course_common.waiting import wait_until
from ros_exercises_testing import Command


def spawn_turtle(node_name, *arguments):
    """rosrun ros_exercises spawn_turtle ...; a node name of its own for each run, since private
    parameters outlive the node that was given them."""
    return run('rosrun', 'ros_exercises', 'spawn_turtle', '__name:=' + node_name, *arguments)


def turtles():
    return {topic.split('/')[1] for topic, _ in rospy.get_published_topics() if topic.endswith('/pose')}


class TestSpawnServices(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_spawn_services')
        cls.exercise4 = Command('roslaunch', 'ros_exercises', 'exercise4.launch')
        cls.exercise4.wait_for(r'Killed the turtle \[turtle1\]')

    @classmethod
    def tearDownClass(cls):
        cls.exercise4.stop()

    def assert_pose(self, turtle, x, y, theta):
        recorder = turtle_poses(turtle)
        try:
            recorder.wait_for_count(1, 10)
            verdict = at_pose(recorder.latest(), (x, y, theta), 1e-5)   # as the grader judges it
            self.assertTrue(verdict.passed, verdict.reason)
        finally:
            recorder.close()

    def test_launch_spawns_robotics_at_one_one_and_kills_turtle1(self):
        self.exercise4.wait_for(r'Spawned the turtle \[robotics\] at x=1.000000, y=1.000000, theta=0.000000')
        self.assert_pose('robotics', 1.0, 1.0, 0.0)
        wait_until(lambda: 'turtle1' not in turtles(), 10, 'turtle1 to be gone')

    def test_spawn_at_arguments(self):
        code, output = spawn_turtle('spawn_second', '7', '8', '1.5', '_name:=second', '_kill:=')
        self.assertEqual(code, 0, output)
        self.assertIn('Spawned the turtle [second] at x=7.000000, y=8.000000, theta=1.500000', output)
        self.assert_pose('second', 7.0, 8.0, 1.5)

    def test_spawn_from_parameters_and_kill(self):
        code, output = spawn_turtle('spawn_victim', '3', '3', '0', '_name:=victim', '_kill:=')
        self.assertEqual(code, 0, output)
        code, output = spawn_turtle('spawn_third', '_x:=9', '_y:=2.5', '_theta:=-1', '_name:=third', '_kill:=victim')
        self.assertEqual(code, 0, output)
        self.assertIn('Killed the turtle [victim]', output)
        self.assert_pose('third', 9.0, 2.5, -1.0)
        wait_until(lambda: 'victim' not in turtles(), 10, 'the turtle victim to be gone')

    def assert_service_error(self, arguments, client_message, simulator_message):
        """The client fails with exit code 1 and its message; turtlesim's reason is in its log and,
        passed on by the service call, in the client's output."""
        code, output = spawn_turtle(*arguments)
        self.assertEqual(code, 1, output)
        self.assertIn(client_message, output)
        self.assertIn(simulator_message, output)
        self.exercise4.wait_for(re.escape(simulator_message))

    def test_taken_name_fails_and_keeps_the_turtle(self):
        self.assert_service_error(['spawn_again', '5', '5', '0', '_name:=robotics', '_kill:='],
                                  'Could not spawn the turtle [robotics]: the name is taken',
                                  'A turtled named [robotics] already exists')
        self.assert_pose('robotics', 1.0, 1.0, 0.0)

    def test_unknown_turtle_fails(self):
        self.assert_service_error(['spawn_fourth', '5', '5', '0', '_name:=fourth', '_kill:=nobody'],
                                  'Could not kill the turtle [nobody]: is there a turtle with that name?',
                                  'Tried to kill turtle [nobody], which does not exist')

    def test_bad_arguments_fail_before_calling_a_service(self):
        turtles_before = turtles()
        for number, (arguments, message) in enumerate([
                (['1', 'abc', '0'], 'x, y and theta must be numbers, got [1] [abc] [0]'),
                (['1', '2'], 'Usage: spawn_turtle [x y theta]'),
                (['20', '1', '0'], "The position (20.000000, 1.000000) is outside turtlesim's world"),
                (['nan', '1', '0'], 'x, y and theta must be numbers'),
                (['_x:=abc'], 'The parameters ~x, ~y and ~theta must be numbers'),
                (['_name:=same', '_kill:=same'], '~kill names the turtle that is being spawned, [same]')]):
            code, output = spawn_turtle('spawn_bad%d' % number, *arguments)
            self.assertEqual(code, 2, output)
            self.assertIn(message, output)
        self.assertEqual(turtles(), turtles_before)

    def test_draw_shape_bad_parameters(self):
        for number, (arguments, message) in enumerate([
                (['_shape:=circle'], '~shape must be square or triangle, got [circle]'),
                (['_side:=abc'], '~side, ~speed and ~turn_speed must be positive numbers'),
                (['_speed:=0'], '~side, ~speed and ~turn_speed must be positive numbers'),
                (['_open_loop:=maybe'], '~open_loop must be true or false'),
                (['_side:=20'], "A square with sides of 20 m from (1.000000, 1.000000) leaves turtlesim's world")]):
            code, output = run('rosrun', 'ros_exercises', 'draw_shape', '__name:=draw_bad%d' % number, *arguments)
            self.assertEqual(code, 1, output)
            self.assertIn(message, output)

    def test_draw_shape_stops_when_its_turtle_is_killed(self):
        code, output = spawn_turtle('spawn_runner', '5', '5', '0', '_name:=runner', '_kill:=')
        self.assertEqual(code, 0, output)
        drawing = Command('rosrun', 'ros_exercises', 'draw_shape', 'robotics/cmd_vel:=runner/cmd_vel',
                          'robotics/pose:=runner/pose')
        try:
            drawing.wait_for(r'Drawing a square')
            rospy.ServiceProxy('/kill', Kill)('runner')
            drawing.wait_for(r'No pose of the turtle for 1 s: was it killed, or turtlesim closed\?')
            wait_until(lambda: drawing.program.process.poll() is not None, 10, 'draw_shape to exit')
        finally:
            self.assertEqual(drawing.stop(), 1)


if __name__ == '__main__':
    rostest.rosrun('ros_exercises', 'test_spawn_services', TestSpawnServices)
