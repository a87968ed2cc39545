"""Rates of arrival and the digits a publisher cycles through (the lab report's exercise 1)."""
import statistics

from course_checks.verdict import Verdict


def rate_of(entries):
    """Messages per second over (arrival time, message) entries, first to last."""
    times = [arrival for arrival, _ in entries]
    return (len(times) - 1) / (times[-1] - times[0])


def kept_rate(times):
    """The rate a publisher keeps: one over the median interval between arrival times (at least
    two). A node on simulated time that starts before the first /clock, or runs late on a busy
    machine, sends two or three at once while rospy.Rate catches up; those bursts move the first
    to last count (rate_of) but not the median. 0.0 when the times do not advance."""
    intervals = [later - earlier for earlier, later in zip(times, times[1:])]
    median = statistics.median(intervals)
    return 1.0 / median if median > 0 else 0.0


def cycles_through(digits, id_number):
    """Whether the digits are the ID's, in order, starting anywhere and wrapping round."""
    expected = [int(digit) for digit in id_number]
    starts = [start for start in range(len(expected))
              if all(digit == expected[(start + i) % len(expected)] for i, digit in enumerate(digits))]
    return Verdict(bool(starts), 'the digits of %s in order' % id_number if starts else
                   'digits %s are not the ID %s over and over' % (digits, id_number))
