#!/usr/bin/env python3
"""draw_square drives turtle1 around a 2 m square from the centre of the (reset) canvas."""
import math
import re
import unittest

import rospy
import rostest

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim_testing import RosoutWatcher

CENTRE = 5.544445
CORNERS = [(CENTRE + 2, CENTRE), (CENTRE + 2, CENTRE + 2), (CENTRE, CENTRE + 2), (CENTRE, CENTRE)]
CORNER_TOLERANCE = 0.25  # the demo stops within 0.1 m of each goal, and the errors add up over the sides


def stops(poses):
    """The poses where the turtle came to rest after moving, in order."""
    result, moving = [], False
    for pose in poses:
        if pose.linear_velocity or pose.angular_velocity:
            moving = True
        elif moving:
            result.append(pose)
            moving = False
    return result


def corners(poses):
    """Rest poses after driving a side (those that are not turns on the spot)."""
    result, previous = [], None
    for pose in stops(poses):
        if previous is None or math.hypot(pose.x - previous.x, pose.y - previous.y) > 1.0:
            result.append(pose)
        previous = pose
    return result


class DrawSquareTest(unittest.TestCase):
    def test_turtle1_drives_around_a_square(self):
        rospy.init_node('draw_square_test')
        rosout = RosoutWatcher()
        poses = TopicRecorder('/turtle1/pose', Pose)
        wait_until(lambda: len(corners(poses.messages(0))) >= 4, 90.0, 'turtle1 to go once around the square')
        found = corners(poses.messages(0))
        for pose, (x, y) in zip(found, CORNERS):
            self.assertAlmostEqual(pose.x, x, delta=CORNER_TOLERANCE, msg=found)
            self.assertAlmostEqual(pose.y, y, delta=CORNER_TOLERANCE, msg=found)
        turned = [pose.theta for pose in stops(poses.messages(0)) if pose not in found]
        self.assertGreaterEqual(len(turned), 3, found)  # a stop after each of the first three turns
        for theta in turned:
            quarter_turns = theta / (math.pi / 2)
            self.assertAlmostEqual(quarter_turns, round(quarter_turns), delta=0.05, msg=turned)
        lines = [text for _, text in rosout.lines('/draw_square')]
        self.assertIn('Reached goal', lines)
        goal_lines = [text for text in lines if text.startswith('New goal')]
        self.assertTrue(goal_lines and all(re.match(r'^New goal \[-?\d+\.\d{6} -?\d+\.\d{6}, -?\d+\.\d{6}\]$', text)
                                           for text in goal_lines), lines)


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'square_path', DrawSquareTest)
