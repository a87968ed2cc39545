#!/usr/bin/env python3
"""wander.py: 120 simulated seconds in turtlebot3_world, no collision, ground covered."""
import math
import os

import rospy
import rostest
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Trigger

from course_checks.robot import largest_move, node_names, travelled
from course_testing.pictures import picture_folder
from move_turtlebot3_testing import LabTestCase, Launch, LoneNode

CELL = 0.5  # m: side of the squares counted as visited


def visited_cells(poses):
    return {(math.floor(x / CELL), math.floor(y / CELL)) for _, x, y, _ in poses}


def lds01_scan(ranges):
    return LaserScan(angle_min=0.0, angle_max=6.28319, angle_increment=6.28319 / 359,
                     range_min=0.12, range_max=3.5, ranges=ranges)


class WanderTest(LabTestCase):

    def wander(self, noise, picture_png=''):
        # In lock step, so that wander.py steers each scan at 20x as at 1x, on a busy machine too.
        self.lock_step()
        self.launch = Launch.package_file('wander.launch', noise_stddev=noise,
                                          real_time_factor=20, picture_png=picture_png)
        self.watch.wait_until_running()
        start = self.watch.now()
        self.watch.wait_sim_seconds(120, timeout=240)
        poses = self.watch.poses_since(start)
        self.assertEqual(self.watch.collisions, 0)
        driven = travelled(poses)
        cells = visited_cells(poses)
        print('wander, noise %.2f: %.1f m travelled, %d cells of %.1f m, %.1f m from the start at '
              'most' % (noise, driven, len(cells), CELL, largest_move(poses)))
        self.assertGreater(driven, 10.0)       # 120 s at 0.22 m/s would be 26 m
        self.assertGreaterEqual(len(cells), 20)   # the arena holds about 90 such squares
        self.assertGreater(largest_move(poses), 2.0)
        return poses

    def test_wanders_turtlebot3_world_without_noise(self):
        self.wander(noise=0.0)

    def test_wanders_turtlebot3_world_with_noise_and_draws_its_trail(self):
        picture = os.path.join(picture_folder('move_turtlebot3', 'wander'), 'wander.png')
        self.wander(noise=0.01, picture_png=picture)
        save_picture = rospy.ServiceProxy('/fake_tb3/save_picture', Trigger)
        answer = save_picture()
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.message, picture)
        with open(picture, 'rb') as png:
            self.assertEqual(png.read(8), b'\x89PNG\r\n\x1a\n')

    def test_odd_scans_never_drive_it_blind(self):
        node = self.launch = LoneNode('wander.py')

        def answer_to(ranges):
            return node.answer_to(lds01_scan(ranges))

        self.assertEqual(answer_to([math.inf] * 360), (0.22, 0.0))   # nothing within range: go
        # a wall 0.3 m ahead, within 10 degrees either side: turn on the spot toward open space
        linear, angular = answer_to([0.3 if i <= 10 or i >= 350 else math.inf for i in range(360)])
        self.assertEqual(linear, 0.0)
        self.assertNotEqual(angular, 0.0)
        self.assertEqual(answer_to([math.nan] * 360), (0.0, 0.0))      # sees nothing: stands
        self.assertEqual(answer_to([0.0] * 360), (0.0, 0.0))           # under range_min: invalid
        self.assertEqual(answer_to([]), (0.0, 0.0))
        self.assertEqual(answer_to([math.inf] * 90)[0], 0.0)     # the right of the front missing
        self.assertEqual(answer_to([-math.inf] * 360)[0], 0.0)   # too close: no forward
        self.assertNotIn('Traceback', node.launch.output)
        self.assertIn('/wander', node_names())

    def test_keeps_turning_one_way_until_the_way_ahead_is_free(self):
        node = self.launch = LoneNode('wander.py')

        def blocked_ahead(open_side):
            # A pillar 0.3 m ahead (15 degrees either side), 1 m all around, open on one side.
            ranges = [1.0] * 360
            for index in range(16, 180):
                ranges[index if open_side == 'left' else 359 - index] = math.inf
            for index in list(range(0, 16)) + list(range(345, 360)):
                ranges[index] = 0.3
            return node.answer_to(lds01_scan(ranges))

        self.assertEqual(blocked_ahead('left'), (0.0, 1.0))
        # The open side changed while it turned (noise, the turn itself): choosing again at each
        # scan could swing it back and forth in front of the pillar for good.
        self.assertEqual(blocked_ahead('right'), (0.0, 1.0))
        self.assertEqual(node.answer_to(lds01_scan([math.inf] * 360)), (0.22, 0.0))
        self.assertEqual(blocked_ahead('right'), (0.0, -1.0))   # a new obstacle: chosen afresh


if __name__ == '__main__':
    rospy.init_node('test_wander')
    rostest.rosrun('move_turtlebot3', 'test_wander', WanderTest)
