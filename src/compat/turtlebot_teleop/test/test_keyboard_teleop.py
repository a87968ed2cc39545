#!/usr/bin/env python3
"""`roslaunch turtlebot_teleop keyboard_teleop.launch` typed at as a user would, in a pseudo-terminal."""
import signal
import subprocess
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist

from course_testing.processes import PtyProgram
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until

TELEOP_TOPIC = '/cmd_vel_mux/input/teleop'
LAUNCH = ['roslaunch', 'turtlebot_teleop', 'keyboard_teleop.launch']


class TeleopInTerminal(unittest.TestCase):
    """Runs `command` in a pseudo-terminal and waits until it is ready for keys."""
    command = LAUNCH

    @classmethod
    def setUpClass(cls):
        cls.twists = TopicRecorder(TELEOP_TOPIC, Twist)

    @classmethod
    def tearDownClass(cls):
        cls.twists.close()

    def sent(self, start=0):
        """(linear.x, angular.z) of every Twist the teleop sent from the start-th on, rounded to the
        printed precision."""
        return [(round(twist.linear.x, 6), round(twist.angular.z, 6)) for twist in self.twists.messages(start)]

    def setUp(self):
        self.teleop = PtyProgram(self.command)
        self.teleop.wait_for_output('currently:\tspeed 0.2\tturn 1', timeout=30)
        self.twists.next_message(10)

    def tearDown(self):
        self.teleop.stop()

    def hold(self, key, velocities, what):
        """Press key every 50 ms, as a held key repeats, until the teleop sends `velocities`."""
        def sent_after_press():
            self.teleop.type(key)
            self.teleop.read_available(0.05)
            return self.sent()[-1] == velocities
        wait_until(sent_after_press, 10, what)


class KeyboardTeleopTest(TeleopInTerminal):

    def test_move_keys_ramp_to_the_default_speeds_and_k_stops(self):
        self.assertEqual(self.sent()[-1], (0.0, 0.0), 'the teleop moves before any key')
        start = self.twists.count()
        self.hold('i', (0.2, 0.0), 'i held to reach 0.2 m/s forward')
        ramp = [linear for linear, _ in self.sent(start)]
        steps = [after - before for before, after in zip(ramp, ramp[1:])]
        self.assertTrue(all(-1e-6 < step < 0.02 + 1e-6 for step in steps),
                        'forward speed did not ramp in steps of 0.02 m/s: %s' % ramp)
        self.teleop.type('k')
        wait_until(lambda: self.sent()[-1] == (0.0, 0.0), 2, 'k to stop at once')
        self.hold('j', (0.0, 1.0), 'j held to turn left at 1 rad/s')
        self.hold(',', (-0.2, 0.0), ', held to go backwards at 0.2 m/s')
        self.teleop.type(' ')
        wait_until(lambda: self.sent()[-1] == (0.0, 0.0), 2, 'space to stop at once')

    def test_letting_go_stops_smoothly(self):
        self.hold('o', (0.2, -1.0), 'o held to reach forward-right')
        wait_until(lambda: self.sent()[-1] == (0.0, 0.0), 5, 'the robot to stop after the key is released')
        stop = self.sent()[-25:]
        self.assertIn((0.18, -0.9), stop, 'no smooth slow-down step in %s' % stop)

    def test_speed_keys_print_the_new_speeds(self):
        for key, line in [('q', 'speed 0.22\tturn 1.1'), ('z', 'speed 0.198\tturn 0.99'),
                          ('w', 'speed 0.2178\tturn 0.99'), ('c', 'speed 0.2178\tturn 0.891')]:
            self.teleop.type(key)
            self.teleop.wait_for_output('currently:\t' + line, timeout=5)
        self.hold('u', (0.2178, 0.891), 'u held to reach the new speeds')

    def test_ctrl_c_stops_the_robot_and_ends_the_launch(self):
        self.hold('i', (0.2, 0.0), 'i held to reach 0.2 m/s forward')
        self.teleop.type('\x03')
        wait_until(lambda: self.teleop.process.poll() is not None, 20, 'roslaunch to end after Ctrl-C')
        self.assertEqual(self.sent()[-1], (0.0, 0.0), 'the last command after Ctrl-C is not a stop')


class ClosedTerminalTest(TeleopInTerminal):
    """Closing the terminal window (SIGHUP) stops the robot like Ctrl-C: no runaway, no traceback."""
    command = ['rosrun', 'turtlebot_teleop', 'turtlebot_teleop_key',
               '__name:=turtlebot_teleop_keyboard', '~cmd_vel:=' + TELEOP_TOPIC]

    def test_hang_up_stops_the_robot(self):
        self.hold('i', (0.2, 0.0), 'i held to reach 0.2 m/s forward')
        self.teleop.process.send_signal(signal.SIGHUP)
        self.assertEqual(self.teleop.process.wait(10), 0)
        self.assertEqual(self.sent()[-1], (0.0, 0.0), 'the last command after the hang-up is not a stop')
        self.assertNotIn('Traceback', self.teleop.read_available())


class NoTerminalTest(unittest.TestCase):
    """Without a terminal there are no keys: one sentence, a failing exit status, no traceback."""

    def check_message(self, output):
        self.assertIn('turtlebot_teleop_key reads the keyboard, but its standard input is not a '
                      'terminal', output)
        self.assertNotIn('Traceback', output)

    def test_rosrun_without_terminal(self):
        result = subprocess.run(['rosrun', 'turtlebot_teleop', 'turtlebot_teleop_key'],
                                stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=30)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stdout, '')
        self.assertEqual(len(result.stderr.splitlines()), 1, result.stderr)
        self.check_message(result.stderr)

    def test_roslaunch_without_terminal_ends(self):
        result = subprocess.run(LAUNCH, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                                timeout=60)
        self.check_message(result.stdout + result.stderr)


if __name__ == '__main__':
    rospy.init_node('keyboard_teleop_test')
    rostest.rosrun('turtlebot_teleop', 'keyboard_teleop', '__main__')
