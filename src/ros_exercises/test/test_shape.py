#!/usr/bin/env python3
"""Exercise 5: the spawned turtle drives the square or triangle of exercise5.launch; its corners are
within 5 cm of where they should be and the path closes within 5 cm, both in the recorded poses and
in the canvas turtlesim saves as a PNG.

Private parameters: ~shape (square or triangle), ~side, ~speed, ~turn_speed (passed to the launch)."""
import os
import shutil
import tempfile
import unittest

import numpy
import rospy
import rostest
from turtlesim.srv import Kill

from course_checks import figures
from course_checks.turtle import pose_array, turtle_poses
from ros_exercises_testing import Command, save_canvas

TOLERANCE = 0.05  # metres
START = (1.0, 1.0, 0.0)  # where exercise5.launch spawns the turtle


class TestShape(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_shape')
        cls.shape = rospy.get_param('~shape')
        cls.side = rospy.get_param('~side')
        cls.outline = figures.polygon(*START, cls.side, {'square': 4, 'triangle': 3}[cls.shape])
        cls.recorder = turtle_poses('robotics')
        cls.exercise5 = Command('roslaunch', 'ros_exercises', 'exercise5.launch', 'shape:=' + cls.shape,
                                'side:=%s' % cls.side, 'speed:=%s' % rospy.get_param('~speed'),
                                'turn_speed:=%s' % rospy.get_param('~turn_speed'))
        cls.exercise5.wait_for(r'Finished the %s' % cls.shape, timeout=120)
        cls.poses = pose_array(cls.recorder)
        # The canvas shows the turtles over the lines; without the turtle, all its path is visible.
        rospy.ServiceProxy('/kill', Kill)('robotics')
        cls.canvas_folder = tempfile.mkdtemp()
        cls.canvas = save_canvas(os.path.join(cls.canvas_folder, cls.shape + '.png'))

    @classmethod
    def tearDownClass(cls):
        cls.recorder.close()
        cls.exercise5.stop()
        shutil.rmtree(cls.canvas_folder)

    def assert_near_outline_corners(self, points, what):
        errors = numpy.hypot(*(points - self.outline).T)
        self.assertLess(errors.max(), TOLERANCE, '%s: %s m from the corners %s' % (what, errors, self.outline.tolist()))

    def test_starts_where_spawned(self):
        self.exercise5.wait_for(r'Spawned the turtle \[robotics\] at x=1.000000, y=1.000000, theta=0.000000')
        self.exercise5.wait_for(r'Drawing a %s with sides of %g m from \(1.000000, 1.000000\)' % (self.shape, self.side))

    def test_turns_at_the_corners(self):
        # The turtle turns on the spot at every corner; the last turn, back to the start heading, is at the start.
        spots = figures.turning_spots(self.poses)
        self.assertEqual(len(spots), len(self.outline), 'turned at %s' % spots.tolist())
        self.assert_near_outline_corners(numpy.roll(spots, 1, axis=0), 'turning spots')

    def test_path_stays_on_the_outline_and_closes(self):
        closed = figures.closed_path(self.poses[:, :2], self.outline, TOLERANCE)   # as the grader judges it
        self.assertTrue(closed.passed, closed.reason)
        self.assertAlmostEqual(self.poses[-1][2], START[2], delta=0.01)

    def test_canvas_corners(self):
        drawn = figures.pen_points(self.canvas)
        self.assert_near_outline_corners(figures.corners_from_sides(drawn, self.outline), 'corners on the canvas')

    def test_canvas_shows_the_whole_closed_outline_and_nothing_else(self):
        drawn = figures.pen_points(self.canvas)
        half_line = 2 / figures.PIXELS_PER_METRE  # the pen is 3 px wide
        self.assertLess(figures.distances_to_polygon(drawn, self.outline).max(), TOLERANCE + half_line)
        # Every 2 cm of the outline, the closing side included, has ink next to it.
        for start, end in zip(self.outline, numpy.roll(self.outline, -1, axis=0)):
            for fraction in numpy.linspace(0, 1, int(self.side / 0.02)):
                point = start + fraction * (end - start)
                self.assertLess(numpy.hypot(*(drawn - point).T).min(), TOLERANCE,
                                'nothing drawn near %s' % point)


if __name__ == '__main__':
    rostest.rosrun('ros_exercises', 'test_shape', TestShape)
