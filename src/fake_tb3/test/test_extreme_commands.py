#!/usr/bin/env python3
"""rostest: the most extreme finite velocity commands (1e308 m/s, 1e308 rad/s, mixes,
denormals) in turtlebot3_world, and light speed in an empty world: both simulators keep odom at
30 Hz, scan at 5 Hz and /clock at 1x, stay up, keep the robot inside the world, warn (throttled)
that they limit the speed, and obey normal commands afterwards."""
import itertools
import math
import threading
import time
import unittest

import rosnode
import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import LaserScan
from std_msgs.msg import UInt32

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window, wait_until
from fake_tb3_testing import rosout_lines

MAX = 1.7976931348623157e308
EXTREME_COMMANDS = [(1e308, 0.0), (0.0, 1e308), (-1e308, 0.0), (0.0, -1e308), (0.0, 1e6),
                    (1e308, 1e308), (-MAX, MAX), (MAX, -1.0), (1.0, -MAX), (5e-324, 1e-310),
                    (-1e6, 1e-300)]
NORMAL_COMMANDS = [(-0.1, 0.0), (0.1, 0.0), (0.0, 1.0), (0.0, -1.0)]
WINDOW = 8.0  # wall seconds over which rates are measured
RATE_TOLERANCE = 0.05
# turtlebot3_world's wall: a hexagon with corners on the x axis, inner apothem 2.54 m.
WALL_NORMALS = [math.radians(30 + 60 * k) for k in range(6)]


def inside_the_wall(x, y):
    return all(x * math.cos(a) + y * math.sin(a) <= 2.54 for a in WALL_NORMALS)


def twist(linear, angular):
    message = Twist()
    message.linear.x, message.angular.z = linear, angular
    return message


class ExtremeCommandsTest(unittest.TestCase):
    def test_extreme_commands(self):
        rospy.init_node('extreme_commands_test')
        recorders = {topic: TopicRecorder(topic, kind) for topic, kind in (
            ('/clock', Clock), ('/odom', Odometry), ('/scan', LaserScan),
            ('/far/clock', Clock), ('/far/odom', Odometry), ('/far/scan', LaserScan),
            ('/collisions', UInt32))}
        rosout = TopicRecorder('/rosout', Log)
        cmd_vel = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        far_cmd_vel = rospy.Publisher('/far/cmd_vel', Twist, queue_size=1, latch=True)
        wait_until(lambda: all(r.latest() for r in recorders.values()), 30, 'every topic')
        wait_until(lambda: cmd_vel.get_num_connections() and far_cmd_vel.get_num_connections(),
                   20, 'both simulators on cmd_vel')

        far_cmd_vel.publish(twist(1e300, 1.0))
        stop = threading.Event()

        def publish_extremes():  # ten a second, round and round
            for command in itertools.cycle(EXTREME_COMMANDS):
                if stop.wait(0.1):
                    return
                cmd_vel.publish(twist(*command))

        publisher = threading.Thread(target=publish_extremes, daemon=True)
        publisher.start()
        measurement_window(1.0)  # the first extreme commands are applied
        start = time.monotonic()
        first_clocks = {t: recorders[t].latest().clock for t in ('/clock', '/far/clock')}
        measurement_window(WINDOW)
        end = time.monotonic()
        stop.set()
        publisher.join()

        measured = []
        for topic, expected in (('/odom', 30.0), ('/scan', 5.0), ('/far/odom', 30.0),
                                ('/far/scan', 5.0)):
            rate = recorders[topic].rate(start, end)
            measured.append('%s %.3f Hz' % (topic, rate))
            self.assertAlmostEqual(rate, expected, delta=RATE_TOLERANCE * expected,
                                   msg='%s at %.3f Hz during the extreme commands' % (topic, rate))
        for topic, first in first_clocks.items():
            simulated = (recorders[topic].latest().clock - first).to_sec()
            measured.append('%s %.3fx' % (topic, simulated / (end - start)))
            self.assertAlmostEqual(simulated / (end - start), 1.0, delta=RATE_TOLERANCE,
                                   msg='%s ran at %.3fx' % (topic, simulated / (end - start)))
        rospy.loginfo('during the extreme commands: %s', ', '.join(measured))
        for _, odom in recorders['/odom'].arrived_since(start):
            position = odom.pose.pose.position
            self.assertTrue(inside_the_wall(position.x, position.y),
                            'the robot left turtlebot3_world: %s' % position)
        far = recorders['/far/odom'].latest().pose.pose.position
        self.assertTrue(math.isfinite(far.x) and math.isfinite(far.y) and far.x > 1e8, far)
        self.assertGreater(recorders['/collisions'].latest().data, 0)
        self.assertIn('/fake_tb3', rosnode.get_node_names())
        self.assertIn('/fake_tb3_empty', rosnode.get_node_names())
        # One warning a second at most says that and why the speed was limited.
        limited = rosout_lines(rosout, 'faster than light')
        self.assertTrue(limited, 'no warning about the limited speed')
        self.assertIn('would move the body faster than light; limited to', limited[0])
        self.assertLessEqual(len(limited), 2 * (WINDOW + 3))  # both simulators, throttled

        # Normal commands are obeyed again: one of these moves the robot off whatever it touches.
        for command in NORMAL_COMMANDS:
            cmd_vel.publish(twist(*command))
            stamp = recorders['/odom'].latest().header.stamp
            odom = wait_until(lambda: recorders['/odom'].latest().header.stamp
                              > stamp + rospy.Duration(0.5) and recorders['/odom'].latest(),
                              10, 'half a simulated second of %s' % (command,))
            if (odom.twist.twist.linear.x, odom.twist.twist.angular.z) == command:
                break
        else:
            self.fail('no normal command moved the robot after the extreme ones')
        cmd_vel.publish(twist(0.0, 0.0))
        wait_until(lambda: recorders['/odom'].latest().twist.twist.linear.x == 0.0
                   and recorders['/odom'].latest().twist.twist.angular.z == 0.0, 10, 'a stop')


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'extreme_commands', ExtremeCommandsTest)
