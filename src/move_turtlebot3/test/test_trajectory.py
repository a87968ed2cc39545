#!/usr/bin/env python3
"""trajectory.py on fake_tb3: the robot drives the circle its commands imply."""

import numpy
import rospy
import rostest

from course_checks.figures import fit_circle
from course_checks.rates import kept_rate
from move_turtlebot3_testing import LabTestCase, Launch


class TrajectoryTest(LabTestCase):

    def drive_circle(self, linear, angular, noise):
        self.launch = Launch.package_file('trajectory.launch', linear=linear, angular=angular,
                                          noise_stddev=noise, real_time_factor=10)
        self.watch.wait_until_running()
        start = self.watch.now()
        period = 2 * numpy.pi / angular
        self.watch.wait_sim_seconds(1.5 * period + 2, timeout=120)
        poses = self.watch.poses_since(start)
        centre_x, centre_y, radius = fit_circle([(x, y) for _, x, y, _ in poses])
        expected = linear / angular
        self.assertAlmostEqual(radius, expected, delta=0.05 * expected)
        # every position lies on that circle, and the circle starts at the spawn pose (0, 0)
        distances = [numpy.hypot(x - centre_x, y - centre_y) for _, x, y, _ in poses]
        self.assertLess(max(abs(d - expected) for d in distances), 0.05 * expected)
        self.assertAlmostEqual(numpy.hypot(centre_x, centre_y), expected, delta=0.05 * expected)
        # counter-clockwise for a positive turn rate: the centre is to the robot's left (+y)
        self.assertGreater(centre_y, 0)
        # the commands come at 1 Hz of simulated time
        commands = [t for t, _, _ in self.watch.copy('commands') if t is not None and t >= start]
        rate = kept_rate(commands)
        self.assertAlmostEqual(rate, 1.0, delta=0.1)
        print('circle of %.2f m/s and %.2f rad/s, noise %.2f: radius %.4f m (expected %.4f), '
              'commands at %.3f Hz' % (linear, angular, noise, radius, expected, rate))
        self.assertEqual(self.watch.collisions, 0)

    def test_slide_speeds_drive_a_circle_of_radius_1_with_noise(self):
        self.drive_circle(1.0, 1.0, noise=0.01)

    def test_other_speeds_drive_a_circle_of_radius_0_4_without_noise(self):
        self.drive_circle(0.2, 0.5, noise=0.0)

    def test_a_speed_that_is_not_a_number_is_a_clear_error(self):
        self.launch = Launch.package_file('trajectory.launch', linear='fast')
        self.launch.wait_for_output('vel_publisher-', timeout=60)
        self.launch.wait_for_output('process has died', timeout=60)
        self.assertIn("/vel_publisher/linear must be a number, not 'fast'", self.launch.output)
        self.assertNotIn('Traceback', self.launch.output)


if __name__ == '__main__':
    rospy.init_node('test_trajectory')
    rostest.rosrun('move_turtlebot3', 'test_trajectory', TrajectoryTest)
