"""Periodic ticks on the simulated clock, and the pace of simulated time against the wall clock."""
import math

import numpy as np
import pytest

from course_common.timing import Pacer, Periodic


def test_periodic_keeps_the_exact_rate():
    odom = Periodic(30.0)
    ticks = []
    while odom.next_ns <= 10 * 10 ** 9:
        ticks.append(odom.next_ns)
        odom.advance()
    assert len(ticks) == 300 and ticks[-1] == 10 * 10 ** 9
    assert set(np.diff(ticks)) == {33333333, 33333334}
    for bad in (0, -5, math.inf, 'fast'):
        with pytest.raises(ValueError, match='odom_rate must be a'):
            Periodic(bad, 'odom_rate')


def test_pacer_runs_simulated_time_at_the_factor_and_gives_up_catching_up():
    pacer = Pacer(10.0, start_wall=100.0)
    assert pacer.due(10 ** 9) == pytest.approx(100.1)  # 1 simulated second, 0.1 wall second
    pacer.reached(10 ** 9, now=100.3)  # 0.2 s late: catches up
    assert pacer.due(2 * 10 ** 9) == pytest.approx(100.2)
    pacer.reached(2 * 10 ** 9, now=101.0)  # 0.8 s late: carries on from here
    assert pacer.due(3 * 10 ** 9) == pytest.approx(101.1)
    assert Pacer(0.5, start_wall=0.0).due(10 ** 9) == pytest.approx(2.0)
    for bad in (0.0, -1.0, math.inf, math.nan):
        with pytest.raises(ValueError, match='real_time_factor must be a positive number'):
            Pacer(bad, start_wall=0.0)


def test_pacer_after_a_hold_goes_on_from_it_without_catching_up():
    pacer = Pacer(10.0, start_wall=100.0)
    pacer.hold(10 ** 9, now=100.5)   # stood at 1 simulated second from 100.1 to 100.5
    assert pacer.due(2 * 10 ** 9) == pytest.approx(100.6)
    pacer.hold(2 * 10 ** 9, now=100.55)   # ahead of its pace (a hold that ended at once): kept
    assert pacer.due(3 * 10 ** 9) == pytest.approx(100.7)
