#!/usr/bin/env python3
"""The whole lab from one terminal: keys typed into teleop_chain.launch drive turtlesim's turtle."""
import math
import os
import unittest

import rospy
import rostest
from PIL import Image
from std_srvs.srv import Trigger

from course_checks.turtle import travelled, turned
from course_testing.pictures import picture_folder
from course_testing.processes import PtyProgram
from course_common.waiting import wait_until
from my_turtle_testing import hold_key, turtle1_poses

SIDE_M = 1.5
# From a k press to the turtle standing still takes up to a teleop pass, a relay loop and a
# simulator tick: let go of a key this long before the goal.
STOP_LATENCY_S = 0.15
SPRITE_RADIUS_M = 0.6  # the saved canvas shows the turtle, which hides the trail beneath it
PIXELS_PER_M = 45
CANVAS_PX = 500
BACKGROUND = (69, 86, 255)
PEN = (179, 184, 255)


def canvas_pixel(x, y):
    """Pixel column and row of a world point (origin bottom-left, y up)."""
    return round(x * PIXELS_PER_M), round(CANVAS_PX - 1 - y * PIXELS_PER_M)


class TeleopChainTest(unittest.TestCase):

    def setUp(self):
        rospy.init_node('teleop_chain_test')
        self.chain = PtyProgram(['roslaunch', 'my_turtle', 'teleop_chain.launch'])
        self.chain.wait_for_output('currently:\tspeed 0.2\tturn 1', timeout=60)
        self.poses = turtle1_poses()

    def tearDown(self):
        self.chain.stop()

    def stop_with_k(self):
        self.chain.type('k')
        self.poses.wait_for(lambda pose: pose.linear_velocity == 0 and pose.angular_velocity == 0,
                            5, 'k to stop the turtle')
        still = self.poses.record(0.5)
        self.assertEqual(travelled(still), 0.0, 'the turtle moves after k')
        self.assertEqual(turned(still), 0.0, 'the turtle turns after k')

    def hold_until(self, key, progress, goal, speed):
        """Hold key until progress(poses since) reaches goal, then k; returns the poses since.
        speed(pose) is how fast progress grows, to let go before the turtle coasts past the goal."""
        first = self.poses.count()

        def arriving():
            coasting = speed(self.poses.latest()) * STOP_LATENCY_S
            return progress(self.poses.entries(first)) + coasting >= goal
        hold_key(self.chain, key, arriving, 30, 'holding %s to reach %.2f' % (key, goal))
        self.stop_with_k()
        return self.poses.entries(first)

    def forward_with_i(self, metres):
        start = self.poses.latest()
        driven = self.hold_until('i', travelled, metres, lambda pose: pose.linear_velocity)
        self.assertAlmostEqual(turned(driven), 0.0, places=4, msg='i turned the turtle')
        end = self.poses.latest()
        heading = math.atan2(end.y - start.y, end.x - start.x)
        self.assertAlmostEqual(math.remainder(heading - start.theta, 2 * math.pi), 0.0, places=2,
                               msg='i did not move the turtle forward')
        return driven

    def left_with_j(self, radians):
        turning = self.hold_until('j', turned, radians, lambda pose: pose.angular_velocity)
        self.assertEqual(travelled(turning), 0.0, 'j moved the turtle')

    def test_keys_drive_the_turtle_around_a_square(self):
        for _ in range(6):  # w: linear speed x1.1 each time
            self.chain.type('w')
        self.chain.wait_for_output('currently:\tspeed 0.354312\tturn 1', timeout=5)
        # Faster still, so that the square takes less of the suite's time: the teleop ramps up at
        # 0.2 m/s and 1 rad/s each second, so most of a side is the ramp.
        for key in 'wwwwwwweeeeeee':   # e: angular speed x1.1 each time
            self.chain.type(key)
        self.chain.wait_for_output('currently:\tspeed 0.690454\tturn 1.94872', timeout=5)
        trail = []
        for _ in range(4):
            trail += self.forward_with_i(SIDE_M)
            self.left_with_j(math.pi / 2)
        self.check_canvas([pose for _, pose in trail])

        self.chain.type('\x03')
        wait_until(lambda: self.chain.process.poll() is not None, 30,
                   'Ctrl-C to end the teleop and with it the whole launch')
        self.assertNotIn('Traceback', self.chain.read_available())

    def check_canvas(self, trail):
        path = rospy.get_param('~canvas_png') or os.path.join(picture_folder('my_turtle', 'teleop_chain'), 'trail.png')
        rospy.set_param('/turtlesim_node/canvas_png', path)
        rospy.wait_for_service('/turtlesim_node/save_canvas', 10)
        reply = rospy.ServiceProxy('/turtlesim_node/save_canvas', Trigger)()
        self.assertTrue(reply.success, reply.message)
        self.assertEqual(reply.message, path)
        canvas = Image.open(path).convert('RGB')
        self.assertEqual(canvas.size, (CANVAS_PX, CANVAS_PX))
        end = trail[-1]
        for pose in trail[::10]:
            if math.hypot(pose.x - end.x, pose.y - end.y) < SPRITE_RADIUS_M:
                continue
            column, row = canvas_pixel(pose.x, pose.y)
            around = {canvas.getpixel((column + dx, row + dy)) for dx in (-1, 0, 1) for dy in (-1, 0, 1)}
            self.assertIn(PEN, around, 'no trail at (%.2f, %.2f)' % (pose.x, pose.y))
        inside_x = sum(pose.x for pose in trail) / len(trail)
        inside_y = sum(pose.y for pose in trail) / len(trail)
        self.assertEqual(canvas.getpixel(canvas_pixel(inside_x, inside_y)), BACKGROUND,
                         'the middle of the square is not background')
        self.assertEqual(canvas.getpixel((5, 5)), BACKGROUND)


if __name__ == '__main__':
    rostest.rosrun('my_turtle', 'teleop_chain', TeleopChainTest)
