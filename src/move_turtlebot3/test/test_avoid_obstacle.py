#!/usr/bin/env python3
"""avoid_obstacle.py on fake_tb3: drives up to a wall, stops 0.35-0.5 m before it, stays there."""
import math

import rospy
import rostest
from sensor_msgs.msg import LaserScan

from course_checks import driving
from course_checks.robot import largest_move, node_names
from course_common.waiting import wait_until
from move_turtlebot3_testing import LabTestCase, Launch, LoneNode

# The wall of world wall_ahead has its face at x = 2.0; the laser sits 0.032 m behind the centre.
WALL_X = 2.0
LASER_BEHIND_CENTRE = 0.032
STAY_SECONDS = 5     # simulated seconds watched after the stop


class AvoidObstacleTest(LabTestCase):

    def start(self, world, x_pos, noise, real_time_factor):
        self.launch = Launch.package_file('avoid_obstacle.launch', world=world, x_pos=x_pos,
                                          y_pos=0.0, noise_stddev=noise, noise_seed=7,
                                          real_time_factor=real_time_factor)
        self.watch.wait_until_running()
        self.launch.wait_for_output('s2 [0]', timeout=60)

    def stopped_for(self, seconds):
        """The pose has not changed over the last `seconds` of simulated time."""
        return driving.stopped_for(self.watch.copy('poses'), seconds)

    def drive_to_the_wall(self, noise):
        # In lock step: without it, the node answers a scan within some wall-clock milliseconds,
        # and at 10x each of them lets the simulated robot drive on ten times as far at 0.5 m/s.
        self.lock_step()
        self.start('wall_ahead', x_pos=-1.0, noise=noise, real_time_factor=10)
        self.assert_laser_sees_the_wall()
        wait_until(lambda: self.watch.copy('poses')[-1][1] > 0.0, timeout=30,
                   what='the robot to drive toward the wall')
        wait_until(lambda: self.stopped_for(1.0), timeout=60, what='the robot to stop')
        first_stop = self.watch.copy('poses')[-1]
        return first_stop

    def assert_laser_sees_the_wall(self):
        """A scan sees the wall where the world has it, from where odometry had the robot then. Not
        necessarily from the spawn pose: the node can answer the first scans, and drive, before this
        test's subscribers have connected (seen on a busy machine: 0.2 m on)."""
        wait_until(lambda: self.watch.copy('poses') and self.watch.copy('scans')[-1].header.stamp.to_sec() >=
                   self.watch.copy('poses')[0][0], timeout=30, what='a scan and a pose before it')
        poses = self.watch.copy('poses')
        scan = next(scan for scan in self.watch.copy('scans') if scan.header.stamp.to_sec() >= poses[0][0])
        _, x, _, _ = [pose for pose in poses if pose[0] <= scan.header.stamp.to_sec()][-1]
        self.assertLess(x, 0.0)   # far from the wall still
        self.assertAlmostEqual(scan.ranges[0], WALL_X - (x - LASER_BEHIND_CENTRE), delta=0.05)

    def assert_front_range_in_band(self):
        x = self.watch.copy('poses')[-1][1]
        # the same, as the laser sees it over the stay, as the grader judges it (a margin for the noise)
        front = driving.front_at_stop(self.watch.copy('scans'), STAY_SECONDS, 0.33, 0.52)
        print('%s: stopped %.3f m before the wall, %s' % (
            self._testMethodName, WALL_X - (x - LASER_BEHIND_CENTRE), front.reason))
        self.assertGreaterEqual(WALL_X - (x - LASER_BEHIND_CENTRE), 0.35)
        self.assertLessEqual(WALL_X - (x - LASER_BEHIND_CENTRE), 0.5)
        self.assertTrue(front.passed, front.reason)

    def assert_stays(self, first_stop, max_creep):
        """No collision, and at most max_creep metres moved in the STAY_SECONDS after the stop."""
        self.watch.wait_sim_seconds(STAY_SECONDS, timeout=30)
        stayed = driving.stayed(self.watch.poses_since(first_stop[0]), self.watch.collisions, max_creep,
                                STAY_SECONDS)
        self.assertTrue(stayed.passed, stayed.reason)

    def test_stops_before_a_wall_and_stays_without_noise(self):
        first_stop = self.drive_to_the_wall(noise=0.0)
        self.assert_stays(first_stop, max_creep=driving.STILL_M)
        self.assert_front_range_in_band()

    def test_stops_before_a_wall_and_stays_with_noise(self):
        first_stop = self.drive_to_the_wall(noise=0.01)
        # One threshold on a noisy beam: stopped just under 0.5 m, a later reading can come out
        # above 0.5 and move the robot once more, by one scan period (0.2 s at 0.5 m/s). Then it
        # is far enough under the threshold for good.
        self.assert_stays(first_stop, max_creep=0.11)
        wait_until(lambda: self.stopped_for(3.0), timeout=30, what='the robot to stay stopped')
        self.assert_front_range_in_band()

    def test_started_closer_than_half_a_metre_it_does_not_move(self):
        self.start('wall_ahead', x_pos=1.65, noise=0.01, real_time_factor=5)
        self.assertLess(self.watch.front_range(), 0.45)
        start = self.watch.now()
        self.watch.wait_sim_seconds(5, timeout=30)
        self.assertLess(largest_move(self.watch.poses_since(start)), 1e-4)
        commands = self.watch.copy('commands')
        self.assertGreater(len(commands), 10)
        self.assertEqual({(linear, angular) for _, linear, angular in commands}, {(0.0, 0.0)})
        self.assertEqual(self.watch.collisions, 0)

    def test_in_the_empty_world_it_keeps_going(self):
        self.start('empty', x_pos=0.0, noise=0.01, real_time_factor=10)
        self.watch.wait_sim_seconds(2, timeout=30)
        start = self.watch.now()
        self.watch.wait_sim_seconds(10, timeout=60)
        poses = self.watch.poses_since(start)
        self.assertAlmostEqual(poses[-1][1] - poses[0][1], 0.5 * (poses[-1][0] - poses[0][0]),
                               delta=0.25)
        self.assertLess(max(abs(y) for _, _, y, _ in poses), 1e-6)
        self.assertEqual(self.watch.front_range(), math.inf)

    def test_odd_scans_stop_the_robot_and_crash_nothing(self):
        node = self.launch = LoneNode('avoid_obstacle.py')

        def forward_speed(ranges):
            return node.answer_to(LaserScan(ranges=ranges))[0]

        self.assertEqual(forward_speed([math.inf] * 360), 0.5)    # nothing within range: go
        self.assertEqual(forward_speed([math.nan] * 360), 0.0)    # no valid reading: stop
        self.assertEqual(forward_speed([1.0] * 360), 0.5)
        self.assertEqual(forward_speed([-math.inf] * 360), 0.0)   # too close to measure: stop
        self.assertEqual(forward_speed([2.0] * 100), 0.5)         # short scan, front beam there
        node.launch.wait_for_output('s1 [270]\nNone', timeout=10)   # its print comes through a pipe, maybe after the answer
        self.assertEqual(forward_speed([]), 0.0)                  # no beams at all: stop
        self.assertEqual(forward_speed([0.3] * 360), 0.0)
        self.assertNotIn('Traceback', node.launch.output)
        self.assertIn('/obstacle_avoidance', node_names())


if __name__ == '__main__':
    rospy.init_node('test_avoid_obstacle')
    rostest.rosrun('move_turtlebot3', 'test_avoid_obstacle', AvoidObstacleTest)
