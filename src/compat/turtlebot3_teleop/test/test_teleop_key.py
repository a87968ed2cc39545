#!/usr/bin/env python3
"""The TurtleBot3 keyboard teleop typed into through a pty, as a student would use it."""
import signal
import subprocess
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist

from course_testing.processes import PtyProgram
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import measurement_window, wait_until

NODE = '/turtlebot3_teleop_keyboard'


def node_names():
    publishers, subscribers, services = rosgraph.Master('/test_teleop_key').getSystemState()
    return {node for _, nodes in publishers + subscribers + services for node in nodes}


class TeleopKeyTest(unittest.TestCase):

    def setUp(self):
        self.cmd_vel = TopicRecorder('cmd_vel', Twist)
        self.teleop = None

    def tearDown(self):
        self.cmd_vel.close()
        if self.teleop is not None:
            self.teleop.stop()

    def messages(self):
        """(linear, angular) of every cmd_vel message."""
        return [(twist.linear.x, twist.angular.z) for twist in self.cmd_vel.messages()]

    def launch(self, model):
        self.teleop = PtyProgram(['roslaunch', 'turtlebot3_teleop', 'turtlebot3_teleop_key.launch',
                                  'model:=' + model])
        self.teleop.wait_for_output('CTRL-C to quit', timeout=30)
        wait_until(self.messages, timeout=10, what='the first cmd_vel message')

    def wait_for_command(self, linear, angular, timeout=10):
        return wait_until(
            lambda: any(abs(l - linear) < 1e-6 and abs(a - angular) < 1e-6
                        for l, a in self.messages()),
            timeout, what='cmd_vel linear %.3f angular %.3f' % (linear, angular))

    def test_keys_ramp_cmd_vel_and_ctrl_c_stops_the_robot(self):
        self.launch('waffle')
        self.assertIn('Control Your TurtleBot3!', self.teleop.output)
        self.assertIn('0.26 m/s', self.teleop.output)
        self.assertIn('1.82 rad/s', self.teleop.output)

        # about every 0.1 s, counted over a window while nothing is typed
        start_count, start = self.cmd_vel.count(), time.monotonic()
        end = measurement_window(2.0, start)
        rate = (self.cmd_vel.count() - start_count) / (end - start)
        self.assertGreater(rate, 7.0)
        self.assertLess(rate, 13.0)

        self.teleop.type('wwww')
        self.teleop.wait_for_output('linear vel 0.04\t angular vel 0.00', timeout=10)
        self.teleop.type('aa')
        self.teleop.wait_for_output('linear vel 0.04\t angular vel 0.20', timeout=10)
        self.wait_for_command(0.04, 0.2)
        linears = [l for l, _ in self.messages()]
        angulars = [a for _, a in self.messages()]
        # the ramp: no jump bigger than 0.005 m/s or 0.05 rad/s between consecutive messages
        self.assertLessEqual(max(abs(b - a) for a, b in zip(linears, linears[1:])), 0.005 + 1e-9)
        self.assertLessEqual(max(abs(b - a) for a, b in zip(angulars, angulars[1:])), 0.05 + 1e-9)
        self.assertIn(0.02, [round(l, 4) for l in linears])  # passed through the intermediate steps

        self.teleop.type('s')
        self.teleop.wait_for_output('linear vel 0.00\t angular vel 0.00', timeout=10)
        self.wait_for_command(0.0, 0.0)

        self.teleop.type('wwwwwwd')
        self.wait_for_command(0.03, -0.1)
        self.teleop.type('\x03')
        wait_until(lambda: NODE not in node_names(), timeout=10, what='the teleop node to exit')
        self.assertEqual(self.messages()[-1], (0.0, 0.0))
        self.assertNotIn('Traceback', self.teleop.output)

    def test_banner_again_after_20_keys_and_unknown_model_uses_burger_limits(self):
        self.launch('rover')
        self.assertIn('Unknown TurtleBot3 model "rover"', self.teleop.output)
        self.assertIn('0.22 m/s', self.teleop.output)
        self.teleop.type('w' * 30)
        self.teleop.wait_for_output('linear vel 0.22\t angular vel 0.00', timeout=10)
        self.assertEqual(self.teleop.output.count('Control Your TurtleBot3!'), 2)
        self.assertNotIn('linear vel 0.23', self.teleop.output)

    def test_closing_the_terminal_stops_the_robot(self):
        self.teleop = PtyProgram(['rosrun', 'turtlebot3_teleop', 'turtlebot3_teleop_key'])
        self.teleop.wait_for_output('CTRL-C to quit', timeout=30)
        self.teleop.type('wwd')
        self.wait_for_command(0.02, -0.1)
        self.teleop.process.send_signal(signal.SIGHUP)  # what closing the terminal window sends
        self.assertEqual(self.teleop.process.wait(10), 0)
        wait_until(lambda: self.messages()[-1] == (0.0, 0.0), timeout=5,
                   what='a zero Twist after the hang-up')
        self.assertNotIn('Traceback', self.teleop.read_available())

    def test_without_a_terminal_it_says_so_and_exits(self):
        result = subprocess.run(['rosrun', 'turtlebot3_teleop', 'turtlebot3_teleop_key'],
                                stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('standard input is not a terminal', result.stderr)
        self.assertNotIn('Traceback', result.stderr + result.stdout)


if __name__ == '__main__':
    rospy.init_node('test_teleop_key')
    rostest.rosrun('turtlebot3_teleop', 'teleop_key', TeleopKeyTest)
