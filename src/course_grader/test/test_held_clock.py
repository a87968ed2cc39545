#!/usr/bin/env python3
"""Exercise 1's held clock (labs.ros_exercises.HeldClockDriver) with the course's publisher, each
message heard by the grader a random while after it came (15 ms on average, as when the grader's
receiving thread waits for the processor on a busy machine): a 50 Hz publisher is measured at
50 Hz, as the grader counts it (100 messages after the first 10), and one at 52 Hz at 52 Hz. And
a 50 Hz publisher whose first 12 messages are heard 80 ms late, the others at once (the grader
kept from the processor while the clock settles), at 50 Hz; one stopped for 1.5 s among the
measured messages (kept from the processor), at 50 Hz, the clock holding for it; and one paused
with the grader (the whole machine paused) for longer than the clock holds, as the clock holds for
its message, at 50 Hz, the clock still holding; and one whose first message is heard before it
has a time (here a message the test hands on before the publisher starts), at 50 Hz; and one that
sleeps 8 simulated seconds before it publishes, heard within the grader's wait for a first message
(the clock's creeps not counted) and measured at 50 Hz. None of them sends more than one message
while the clock stands still for a second halfway (publisher_verdict's `still`), while one timed by
the wall clock goes on: at 25 Hz it is measured on the wall clock at 25 Hz (the held clock waited
for each of its messages, 50.00 Hz), at 50 Hz at 50 Hz."""
import collections
import os
import random
import re
import signal
import subprocess
import time
import unittest

import rospy
import rostest
from std_msgs.msg import Int32

from course_checks import rates
from course_grader import rubric as rubrics
from course_grader.labs.ros_exercises import HeldClockDriver
from course_common.processes import stop_process_group
from course_common.waiting import wait_until

SKIPPED, MESSAGES = 10, 100
EXERCISE1_PUBLISHER = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'exercise1_publisher.py')


class LateHearingDriver(HeldClockDriver):
    """The grader's driver, message k handed on lateness(k) seconds late; after pause_machine(), the
    machine paused once after the 40th message: the publisher stopped on the step before a hold
    (its message not yet due), then the grader too as the clock holds, both continued `seconds`
    later."""

    def __init__(self, lateness, *args):
        self.lateness = lateness
        self.handed_on = 0
        self.pausing = None   # (the publisher's process group, seconds) until the pause is made
        self.publisher_stopped = False
        self.pauser = None
        super().__init__(*args)

    def pause_machine(self, group, seconds):
        self.pausing = (group, seconds)

    def _heard_within(self, seconds):
        if self.pausing and self.handed_on >= 40:
            group, paused_for = self.pausing
            if seconds != self.PATIENCE:   # a creep: on the step before the hold
                os.killpg(group, signal.SIGSTOP)
                self.publisher_stopped = True
            elif self.publisher_stopped:   # the clock holds for the stopped publisher's message
                self.pausing = None
                self.pauser = subprocess.Popen(['sh', '-c', 'kill -s STOP %d; sleep %s; kill -s CONT %d; kill -s CONT -- -%d' % (
                    os.getpid(), paused_for, os.getpid(), group)])
        return super()._heard_within(seconds)

    def _heard(self, message):
        time.sleep(self.lateness(self.handed_on))   # the delay the test adds, not a wait
        self.handed_on += 1
        super()._heard(message)


class HeldClockTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('held_clock_test')
        rospy.set_param('/use_sim_time', True)   # for the publisher, after this node read it

    def measured(self, rate, seed, lateness=None, stopped_for=0.0, machine_paused_for=0.0,
                 heard_before_its_clock=False, publisher_command=('rosrun', 'ros_exercises', 'publisher'),
                 on_the_clock=True):
        """The rate measured of the publisher at `rate`, each message heard lateness(k) seconds late
        (by default a random while, 15 ms on average, drawn from `seed`), the publisher stopped for
        `stopped_for` seconds after the 40th message, or paused with the grader for
        `machine_paused_for` seconds (LateHearingDriver.pause_machine), or its first message heard
        before it has a time (`heard_before_its_clock`: one handed on before it starts, one of those
        left out); publisher_command: the course's publisher unless given; on_the_clock: it is timed by
        the simulated clock, and so sends at most one message while the clock stands still (two, one
        queued), and is not taken for one on the wall clock (asserted). self.held says whether
        the clock still held at the end (it had not taken the publisher for a slower one),
        self.paused whether the machine was paused as asked, self.first_after the wall seconds from
        the publisher's start to its first message heard, self.waited_at_first those the grader
        counts (HeldClockDriver.waited_for_first), self.verdict the grader's (publisher_verdict, at 50
        Hz), self.still_heard how many messages came while the clock stood still, self.story the
        clock and the intervals measured (a failure's message)."""
        randomly = random.Random(seed)

        def a_random_while(_):
            return randomly.expovariate(1 / 0.015)
        driver = LateHearingDriver(lateness or a_random_while, '/ZabirovaKostyukova', Int32, 0.02, 5, SKIPPED,
                                   SKIPPED + MESSAGES // 2)   # as the grader
        if heard_before_its_clock:
            driver._heard(Int32(4))
        started = time.monotonic()
        publisher = subprocess.Popen(list(publisher_command) + ['_rate:=%g' % rate, '_id:=4095127',
                                                                '__name:=publisher_%d' % seed],
                                     stdout=subprocess.DEVNULL, start_new_session=True)
        try:
            wait_until(lambda: len(driver.entries) > heard_before_its_clock, 60, 'the publisher\'s first message')
            self.first_after, self.waited_at_first = time.monotonic() - started, driver.waited_at_first
            if machine_paused_for:
                driver.pause_machine(publisher.pid, machine_paused_for)
            if stopped_for:
                wait_until(lambda: len(driver.entries) >= 40, 60, 'the publisher\'s first 40 messages')
                os.killpg(publisher.pid, signal.SIGSTOP)
                time.sleep(stopped_for)   # how long the test keeps it stopped, not a wait
                os.killpg(publisher.pid, signal.SIGCONT)
            wait_until(lambda: driver.measured(SKIPPED + MESSAGES, 1.5 * (SKIPPED + MESSAGES) / 50), 60,
                       'the publisher\'s messages, as the grader waits for them')
            self.assertIsNotNone(driver.still, 'the clock did not stand still')
            measured = driver.entries[SKIPPED:SKIPPED + MESSAGES]
            self.verdict = rates.publisher_verdict([(stamp, digit.data) for stamp, digit in driver.entries],
                                                   SKIPPED, SKIPPED + MESSAGES, 50, 1.0, '4095127', driver.still)
            self.still_heard = len(driver.still[1])
            self.held, self.paused = not driver.clock.gave_up, driver.pauser is not None
            intervals = collections.Counter(round((later - earlier) * 1000)
                                            for (earlier, _), (later, _) in zip(measured, measured[1:]))
            self.story = ('the clock holding at the end: %s; the machine paused: %s; heard while it stood still: %d; '
                          'intervals (ms: how many): %s' % (self.held, self.paused, self.still_heard,
                                                             dict(sorted(intervals.items()))))
            print('%s: %s' % (self.id(), self.story))   # kept in the test's result file
            if on_the_clock:
                self.assertLess(self.still_heard, rates.WALL_TIMED_MESSAGES, self.story)
                self.assertNotIn('wall clock', self.verdict.reason)
            return rates.rate_of(measured)
        finally:
            driver.close()
            stop_process_group(publisher)
            if driver.pauser:
                driver.pauser.wait()

    def test_a_50_hz_publisher_heard_late_is_measured_at_50_hz(self):
        for seed in (1, 2, 3):
            self.assertAlmostEqual(self.measured(50, seed), 50.0, delta=0.5, msg=self.story)

    def test_a_50_hz_publisher_heard_late_while_the_clock_settles_is_measured_at_50_hz(self):
        # With 10 ms creeps while the clock settled, such stamps were left steps late and caught up
        # among the measured messages, counted from first to last: 51.24 Hz, beyond the rubric's
        # tolerance. On a busy host a few steps of 4 ms can still be left (CI: 3 steps, then 8), each
        # 0.1 Hz counted from first to last, 0.01 to 0.02 Hz fitted (rates.rate_of: 50.04 and 50.14 Hz):
        # the same margin as the other cases, half the rubric's tolerance.
        def late_at_first(k):
            return 0.08 if k < SKIPPED + 2 else 0.0
        self.assertAlmostEqual(self.measured(50, 5, late_at_first), 50.0, delta=0.5, msg=self.story)

    def test_a_50_hz_publisher_stopped_for_a_while_is_measured_at_50_hz(self):
        # With 1 s of patience the clock took it for a slower publisher and ran on at 5 times real
        # time, faster than a publisher on a busy machine follows: 12 to 16 Hz.
        self.assertAlmostEqual(self.measured(50, 6, stopped_for=1.5), 50.0, delta=0.5, msg=self.story)
        self.assertTrue(self.held, 'the clock gave up holding for the stopped publisher')

    def test_a_50_hz_publisher_paused_with_the_grader_while_the_clock_holds_is_measured_at_50_hz(self):
        # A paused machine says nothing of the publisher: counted against it (3 wall seconds), the
        # clock took it for a slower publisher and ran on: 17.4 Hz (CI's failures of this file: 11.7,
        # 13.6 Hz, then a publisher stopped 1.5 s measured off 50 Hz).
        self.assertAlmostEqual(self.measured(50, 7, machine_paused_for=HeldClockDriver.PATIENCE + 0.5), 50.0,
                               delta=0.5, msg=self.story)
        self.assertTrue(self.paused, 'the machine was not paused while the clock held')
        self.assertTrue(self.held, 'the clock gave up holding for the paused publisher; ' + self.story)

    def test_a_50_hz_publisher_heard_before_it_has_a_time_is_measured_at_50_hz(self):
        # As when its first message, sent at time zero, comes before its /clock subscription is
        # connected: roscpp sleeps from zero until a period after the first time it hears. Held one
        # period after that message, the clock waited until it gave up: 14 Hz (the signature of
        # 11.0 Hz in ./test.sh and 14.4 Hz in CI). It holds from a period after the first message.
        self.assertAlmostEqual(self.measured(50, 8, heard_before_its_clock=True), 50.0, delta=0.5, msg=self.story)
        self.assertTrue(self.held, 'the clock gave up holding for the publisher; ' + self.story)

    def test_a_50_hz_publisher_that_sleeps_8_simulated_seconds_first_is_heard_in_time_at_50_hz(self):
        # Creeping 100 ms at each step before the first message (250 steps a simulated second), the
        # clock took 25 s of wall time over one simulated second, longer than the grader waits for a
        # first message: 0 arrived, 0 points. At 10 ms a step a second took 2.7 s, and 8 s 22.6 s:
        # the creeps are the grader's, and the wait no longer counts them.
        self.assertAlmostEqual(self.measured(50, 9, publisher_command=[EXERCISE1_PUBLISHER, '_sleep:=8']), 50.0,
                               delta=0.5, msg=self.story)
        waits = rubrics.load('ros_exercises').limits['start_seconds']
        self.assertLess(self.waited_at_first, waits, 'the first message was heard %.1f s after the publisher started '
                        '(%.1f s without the creeps); the grader waits %g s' % (
                            self.first_after, self.waited_at_first, waits))
        self.assertGreater(self.first_after, waits, 'the clock crept no longer than the grader waits: the case '
                           'shows nothing (%.1f s)' % self.first_after)

    def test_a_52_hz_publisher_heard_late_is_measured_at_52_hz(self):
        self.assertAlmostEqual(self.measured(52, 4), 52.0, delta=0.5, msg=self.story)   # beyond the rubric's 1 Hz

    def test_a_25_hz_publisher_on_the_wall_clock_is_measured_on_it_at_25_hz(self):
        # The clock held for each of its messages as for one the machine delayed: 50.00 Hz, 2 points.
        self.measured(25, 10, publisher_command=[EXERCISE1_PUBLISHER, '_clock:=wall'], on_the_clock=False)
        self.assertFalse(self.verdict.passed, self.verdict.reason)
        self.assertRegex(self.verdict.reason, r'seen \d+ messages in 1 s while the simulated clock \(/clock\) stood '
                         r'still: the publisher is timed by the wall clock, .* on the wall clock: 2[45]\.\d\d Hz$')

    def test_a_50_hz_publisher_on_the_wall_clock_is_measured_on_it_at_50_hz(self):
        # Measured on the wall clock, as the grader hears it: a busy machine moves it, as it would any
        # wall-clock measurement (the reason for the held clock); here within 3 Hz.
        self.measured(50, 11, publisher_command=[EXERCISE1_PUBLISHER, '_clock:=wall'], on_the_clock=False)
        wall_rate = re.search(r'on the wall clock: (\d+\.\d+) Hz$', self.verdict.reason)
        self.assertIsNotNone(wall_rate, self.verdict.reason)
        self.assertAlmostEqual(float(wall_rate.group(1)), 50.0, delta=3.0, msg=self.verdict.reason)


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'held_clock', HeldClockTest)
