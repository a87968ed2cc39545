"""course_checks.rates: the rate a publisher keeps, and its rate from first to last arrival."""
import pytest

from course_checks.rates import kept_rate, rate_of


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
