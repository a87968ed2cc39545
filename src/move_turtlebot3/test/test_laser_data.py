#!/usr/bin/env python3
"""laser_data.py on fake_tb3 prints the scan's ranges; the slide's shell commands work meanwhile."""
import math

import rospy
import rostest
from sensor_msgs.msg import LaserScan

from course_checks import laser
from course_checks.laser import printed_blocks
from course_checks.robot import node_names
from course_testing.processes import run
from course_common.waiting import wait_until
from move_turtlebot3_testing import LabTestCase, Launch

BEAMS = [0, 90, 180, 270, 359]   # the slide's five beams
BLOCKS = 10                      # printed scans checked


class LaserDataTest(LabTestCase):

    def start(self, noise):
        self.launch = Launch.package_file('laser_data.launch', noise_stddev=noise,
                                          real_time_factor=2)
        self.watch.wait_until_running()
        wait_until(lambda: len(printed_blocks(self.launch.lines)) >= BLOCKS, timeout=60,
                   what='%d scans printed by laser_data.py' % BLOCKS)

    def assert_printed_values_are_scan_ranges(self):
        """As the grader judges them."""
        blocks = printed_blocks(self.launch.lines)
        printed = laser.printed_scans(blocks, self.watch.copy('scans'), BEAMS, BLOCKS)
        self.assertTrue(printed.passed, printed.reason)
        return blocks

    def test_printed_values_equal_the_scan_with_noise(self):
        self.start(noise=0.01)
        blocks = self.assert_printed_values_are_scan_ranges()
        self.assertGreater(len(set(map(tuple, blocks))), 1, 'with noise the scans differ')

    def test_printed_values_equal_the_scan_without_noise_and_match_the_world(self):
        self.start(noise=0.0)
        block = self.assert_printed_values_are_scan_ranges()[-1]
        # Spawn (-2.0, -0.5) facing +x in turtlebot3_world, laser 0.032 m behind the centre; beam i
        # looks i * 6.28319/359 rad to the left (beam 90 at 90.25 degrees). Nothing within 3.5 m
        # ahead; the slanted walls of the hexagon 2.045 m to the left and 0.609 m behind.
        self.assertEqual(block[0], 'inf')
        self.assertAlmostEqual(float(block[1]), 2.045, delta=0.003)
        self.assertAlmostEqual(float(block[2]), 0.609, delta=0.003)

    def test_slide_shell_commands_while_the_simulation_runs(self):
        self.start(noise=0.01)
        code, text = run('rostopic', 'list')
        self.assertEqual(code, 0, text)
        for topic in ('/scan', '/cmd_vel', '/odom', '/clock'):
            self.assertIn(topic, text.split())
        code, text = run('rostopic', 'info', 'scan')
        self.assertEqual(code, 0, text)
        self.assertIn('Type: sensor_msgs/LaserScan', text)
        self.assertIn('/fake_tb3', text.split('Subscribers:')[0])   # publisher
        self.assertIn('/laser_data', text.split('Subscribers:')[1])
        code, text = run('rosmsg', 'show', 'LaserScan')
        self.assertEqual(code, 0, text)
        for field in ('float32 angle_min', 'float32 range_max', 'float32[] ranges',
                      'float32[] intensities'):
            self.assertIn(field, text)
        code, text = run('rostopic', 'echo', '-n', '1', 'scan')
        self.assertEqual(code, 0, text)
        fields = dict(line.split(': ', 1) for line in text.splitlines() if line.startswith(
            ('angle_', 'range_m')))
        self.assertEqual(float(fields['angle_min']), 0.0)
        self.assertAlmostEqual(float(fields['angle_max']), 6.28319, places=5)
        self.assertAlmostEqual(float(fields['range_min']), 0.12, places=6)
        self.assertEqual(float(fields['range_max']), 3.5)
        ranges = text.split('ranges: [')[1].split(']')[0].split(',')
        self.assertEqual(len(ranges), 360)
        code, text = run('rosnode', 'list')
        self.assertEqual(code, 0, text)
        self.assertIn('/laser_data', text.split())

    def test_odd_scans_are_printed_without_a_crash(self):
        self.launch = Launch('rosrun', 'move_turtlebot3', 'laser_data.py', 'scan:=odd_scan')
        publisher = rospy.Publisher('odd_scan', LaserScan, queue_size=10)
        wait_until(lambda: publisher.get_num_connections() > 0, timeout=30,
                   what='laser_data.py to subscribe')
        short = LaserScan(ranges=[1.5] * 100)
        invalid = LaserScan(ranges=[1.0] * 360)
        invalid.ranges[0], invalid.ranges[90], invalid.ranges[180] = math.nan, math.inf, -math.inf
        invalid.ranges[270], invalid.ranges[359] = 0.0, 3.5
        for scan in (short, invalid, LaserScan(), short):
            publisher.publish(scan)
        wait_until(lambda: len(printed_blocks(self.launch.lines)) >= 4, timeout=30,
                   what='four scans printed')
        blocks = printed_blocks(self.launch.lines)
        self.assertEqual(blocks[0], ['1.5', '1.5', 'no beam 180 (the scan has 100)',
                                     'no beam 270 (the scan has 100)',
                                     'no beam 359 (the scan has 100)'])
        self.assertEqual(blocks[1], ['nan', 'inf', '-inf', '0.0', '3.5'])
        self.assertEqual(blocks[2], ['no beam %d (the scan has 0)' % i for i in BEAMS])
        self.assertNotIn('Traceback', self.launch.output)
        self.assertIn('/laser_data', node_names())
        publisher.unregister()


if __name__ == '__main__':
    rospy.init_node('test_laser_data')
    rostest.rosrun('move_turtlebot3', 'test_laser_data', LaserDataTest)
