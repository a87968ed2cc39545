#!/usr/bin/env python3
"""Exercises 0 and 1: the digits of the ID arrive in order at 50 Hz and at 1 Hz, the subscriber
prints each of them, and bad parameters stop the publisher with a clear message."""
import unittest

import rospy
import rostest
from std_msgs.msg import Int32

from course_checks import rates
from course_checks.rates import rate_of
from course_testing.processes import run
from course_common.topic_recorder import TopicRecorder

from ros_exercises_testing import Command

FAST_ID = '4095127'
SLOW_ID = '907'


def assert_cycles_through(test, digits, id_number):
    verdict = rates.cycles_through(digits, id_number)
    test.assertTrue(verdict.passed, verdict.reason)


class TestPublisherSubscriber(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_publisher_subscriber')
        cls.fast = TopicRecorder('/ZabirovaKostyukova', Int32)
        cls.slow = TopicRecorder('/slow', Int32)
        cls.exercise1 = Command('roslaunch', 'ros_exercises', 'exercise1.launch', 'rate:=50', 'id:=' + FAST_ID)
        cls.slow_publisher = Command('rosrun', 'ros_exercises', 'publisher', '_rate:=1', '_id:=' + SLOW_ID,
                                     'ZabirovaKostyukova:=slow', '__name:=slow_publisher')

    @classmethod
    def tearDownClass(cls):
        cls.exercise1.stop()
        cls.slow_publisher.stop()

    def test_50_hz_within_2_percent(self):
        # The first digits after connecting are left out: they may arrive bunched.
        self.fast.wait_for_count(161, 30)
        rate = rate_of(self.fast.entries()[10:161])
        self.assertAlmostEqual(rate, 50.0, delta=1.0, msg='measured %.2f Hz' % rate)

    def test_1_hz_within_2_percent(self):
        self.slow.wait_for_count(7, 30)
        rate = rate_of(self.slow.entries()[1:7])
        self.assertAlmostEqual(rate, 1.0, delta=0.02, msg='measured %.4f Hz' % rate)

    def test_digits_in_order(self):
        self.fast.wait_for_count(3 * len(FAST_ID), 30)
        self.slow.wait_for_count(4, 30)
        assert_cycles_through(self, [digit.data for digit in self.fast.messages()], FAST_ID)
        assert_cycles_through(self, [digit.data for digit in self.slow.messages()], SLOW_ID)

    def test_subscriber_prints_each_digit(self):
        self.exercise1.wait_for(r'Publishing the digits of %s at 50 Hz' % FAST_ID)
        printed = self.exercise1.wait_for(r'I heard: \[(\d+)\]', count=3 * len(FAST_ID))
        assert_cycles_through(self, [int(digit) for digit in printed], FAST_ID)

    def test_bad_parameters_stop_the_publisher_with_a_message(self):
        # A node name of its own for each run: a private parameter outlives the node that was given it.
        for number, (argument, message) in enumerate([('_id:=12a4', 'must be a non-empty string of digits'),
                                                      ('_id:=', 'must be a non-empty string of digits'),
                                                      ('_rate:=-5', 'must be a positive number of Hz'),
                                                      ('_rate:=fast', 'must be a positive number of Hz')]):
            code, output = run('rosrun', 'ros_exercises', 'publisher', argument, '__name:=bad_publisher%d' % number)
            self.assertNotEqual(code, 0, argument)
            self.assertIn(message, output, argument)

    def test_long_id_on_the_command_line(self):
        # Too long for an int, roscpp passes it on as a double.
        publisher = Command('rosrun', 'ros_exercises', 'publisher', '_id:=12345678901', '_rate:=50',
                            'ZabirovaKostyukova:=long', '__name:=long_publisher')
        try:
            publisher.wait_for(r'Publishing the digits of 12345678901 at 50 Hz')
        finally:
            self.assertEqual(publisher.stop(), 0)


if __name__ == '__main__':
    rostest.rosrun('ros_exercises', 'test_publisher_subscriber', TestPublisherSubscriber)
