#!/usr/bin/env python3
"""turtlesim on a simulated clock (/use_sim_time) at 5x: /clock at the factor, a pose every
tick of simulated time, one command moving the turtle for one simulated second, the original's log
lines and services, and a node's rospy.Rate following the clock."""
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window, wait_until
from turtlesim.msg import Pose
from turtlesim.srv import Spawn, TeleportAbsolute
from turtlesim.world import TICK_SECONDS
from turtlesim_testing import ONE_COMMAND_TICKS, RosoutWatcher, connected_publisher, moved, twist

REAL_TIME_FACTOR = 5.0


class SimTimeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('turtlesim_sim_time_test')  # on simulated time: the launch sets /use_sim_time
        cls.rosout = RosoutWatcher()
        cls.clock = TopicRecorder('/clock', Clock)
        cls.pose = TopicRecorder('/turtle1/pose', Pose)
        cls.pose.next_message(30.0)
        cls.clock.next_message(30.0)   # a pose may come before this node's /clock connection is up

    def sim_now(self):
        return self.clock.latest().clock.to_sec()

    def test_the_clock_runs_at_the_real_time_factor_and_this_node_follows_it(self):
        start_wall, start_sim = time.monotonic(), self.sim_now()
        end_wall = measurement_window(3.0, start_wall)
        factor = (self.sim_now() - start_sim) / (end_wall - start_wall)
        self.assertAlmostEqual(factor, REAL_TIME_FACTOR, delta=0.2 * REAL_TIME_FACTOR)
        self.assertAlmostEqual(rospy.get_time(), self.sim_now(), delta=0.1)
        # rospy.Rate sleeps in simulated time: 20 periods of 0.1 s take about 2 / 5 wall seconds.
        rate, wall = rospy.Rate(10), time.monotonic()
        sim = rospy.get_time()
        for _ in range(20):
            rate.sleep()
        self.assertAlmostEqual(rospy.get_time() - sim, 2.0, delta=0.1)
        self.assertLess(time.monotonic() - wall, 2.0 / REAL_TIME_FACTOR * 2.5)

    def test_a_pose_every_tick_of_simulated_time(self):
        start = self.pose.count()
        first_sim = self.sim_now()
        wait_until(lambda: self.sim_now() >= first_sim + 4.0, 20.0, '4 simulated seconds')
        count, simulated = self.pose.count() - start, self.sim_now() - first_sim
        self.assertAlmostEqual(count / simulated, 1 / TICK_SECONDS, delta=0.03 / TICK_SECONDS)

    def test_one_command_moves_the_turtle_for_one_simulated_second(self):
        rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(2.0, 5.0, 0.0)
        wait_until(lambda: abs(self.pose.next_message().x - 2.0) < 1e-6, 5.0, 'the teleport')
        cmd_vel = connected_publisher('/turtle1/cmd_vel', Twist)
        stopped = moved(lambda: cmd_vel.publish(twist(1.0)), self.pose)
        self.assertAlmostEqual(stopped.x - 2.0, ONE_COMMAND_TICKS * TICK_SECONDS, delta=0.02)  # at 1 m/s
        self.assertAlmostEqual(stopped.y, 5.0, places=5)

    def test_log_lines_and_services_are_the_originals(self):
        start = self.rosout.count()
        rospy.wait_for_service('/clear', 10.0)
        rospy.ServiceProxy('/clear', Empty)()
        self.rosout.wait_for_line('INFO', 'Clearing turtlesim.', start)
        start = self.rosout.count()
        self.assertEqual(rospy.ServiceProxy('/spawn', Spawn)(1.0, 2.0, 0.5, 'leo').name, 'leo')
        self.rosout.wait_for_line('INFO', 'Spawning turtle [leo] at x=[1.000000], y=[2.000000], theta=[0.500000]',
                                  start)
        start = self.rosout.count()
        rospy.ServiceProxy('/leo/teleport_absolute', TeleportAbsolute)(12.0, 3.0, 0.0)
        self.rosout.wait_for_line('WARN', 'Oh no! I hit the wall! (Clamping from [x=12.000000, y=8.088889])', start)


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'sim_time', SimTimeTest)
