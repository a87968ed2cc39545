"""course_checks.rates: the rate a publisher keeps, and its rate from first to last arrival."""
import pytest

from course_checks.rates import HeldClock, kept_rate, rate_of


def test_a_steady_publisher_keeps_its_rate():
    times = [10.0 + i for i in range(12)]
    assert kept_rate(times) == pytest.approx(1.0)
    assert rate_of([(t, None) for t in times]) == pytest.approx(1.0)


def test_catch_up_bursts_do_not_change_the_kept_rate():
    # 1 Hz, but late twice: three sent at once each time while rospy.Rate catches up
    times = [0.0, 1.0, 2.0, 2.9, 2.95, 3.0, 4.0, 5.0, 6.0, 7.0, 7.9, 7.95, 8.0, 9.0, 10.0]
    assert kept_rate(times) == pytest.approx(1.0)
    assert rate_of([(t, None) for t in times]) == pytest.approx(1.4)   # what the count alone says


def test_a_faster_publisher_is_seen_faster():
    assert kept_rate([i * 0.8 for i in range(15)]) == pytest.approx(1.25)


def test_times_that_do_not_advance_give_no_rate():
    assert kept_rate([3.0, 3.0, 3.0]) == 0.0


def _run(clock, publishes_at, steps, runs_every=1):
    """Steps the clock, a publisher publishing each of publishes_at once the clock has reached it
    and the publisher has the processor (one step in `runs_every`); a hold with nothing due is given
    up (a slower publisher). Returns the stamps of the messages."""
    stamps, due = [], list(publishes_at)
    for step in range(steps):
        if due and clock.now_ns >= due[0] and step % runs_every == 0:
            due.pop(0)
            stamps.append(clock.heard())
        elif clock.next_ns() is None and not (due and clock.now_ns >= due[0]):
            clock.give_up()
    return stamps


def test_the_held_clock_stamps_a_publisher_at_its_rate():
    stamps = _run(HeldClock(20000000, 1000000), [k * 20000000 + 3000000 for k in range(20)], 1000)
    assert rate_of([(t, None) for t in stamps]) == pytest.approx(50.0)
    # Steps that do not divide the period: it holds where the period ends all the same.
    stamps = _run(HeldClock(20000000, 3000000), [k * 20000000 + 3000000 for k in range(20)], 1000)
    assert rate_of([(t, None) for t in stamps]) == pytest.approx(50.0)


def test_a_publisher_kept_from_the_processor_keeps_its_rate_within_one_period_in_n():
    # 50 Hz from 3 ms on: the publisher runs one step in 50 (on its own clock, 50 ms: 2.5 periods).
    stamps = _run(HeldClock(20000000, 1000000), [k * 20000000 + 3000000 for k in range(100)], 100000, 50)
    assert len(stamps) == 100
    assert rate_of([(t, None) for t in stamps]) == pytest.approx(50.0, rel=1 / 99)
    assert stamps[-1] - stamps[-2] == pytest.approx(0.02)   # held where the period ends


def test_the_held_clock_waits_for_a_late_message():
    clock = HeldClock(20000000, 1000000)
    clock.next_ns()
    clock.heard()
    assert [clock.next_ns() for _ in range(21)][-2:] == [21000000, None]   # held one period on
    assert clock.next_ns() is None
    assert clock.heard() == pytest.approx(0.021)   # the late message is stamped where it held


def test_a_slower_publisher_is_stamped_at_its_own_rate_and_the_clock_holds_no_more():
    clock = HeldClock(20000000, 1000000)
    stamps = _run(clock, [k * 100000000 for k in range(1, 8)], 1000)
    assert rate_of([(t, None) for t in stamps]) == pytest.approx(10.0)
    assert clock.hold_ns is None and not clock.holding()
