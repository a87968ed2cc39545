"""Rates of arrival and the digits a publisher cycles through (the lab report's exercise 1)."""
from course_checks.verdict import Verdict


def rate_of(entries):
    """Messages per second over (arrival time, message) entries, first to last."""
    times = [arrival for arrival, _ in entries]
    return (len(times) - 1) / (times[-1] - times[0])


def cycles_through(digits, id_number):
    """Whether the digits are the ID's, in order, starting anywhere and wrapping round."""
    expected = [int(digit) for digit in id_number]
    starts = [start for start in range(len(expected))
              if all(digit == expected[(start + i) % len(expected)] for i, digit in enumerate(digits))]
    return Verdict(bool(starts), 'the digits of %s in order' % id_number if starts else
                   'digits %s are not the ID %s over and over' % (digits, id_number))
