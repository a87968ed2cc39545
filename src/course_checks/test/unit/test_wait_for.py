"""course_common.waiting: a wait that times out is an answer (False), never an assertion."""
import time

from course_common.waiting import Deadline, wait_for


def test_a_condition_that_holds_is_true():
    calls = []
    assert wait_for(lambda: calls.append(1) or len(calls) >= 3, 5, poll=0.001) is True


def test_a_time_out_is_false_not_an_error():
    started = time.monotonic()
    assert wait_for(lambda: False, 0.05, poll=0.01) is False
    assert 0.05 <= time.monotonic() - started < 1


def test_giving_up_ends_the_wait_at_once_with_false():
    started = time.monotonic()
    assert wait_for(lambda: False, 30, gave_up=lambda: True) is False
    assert time.monotonic() - started < 1


def test_a_deadline_leaves_at_least_a_little_time():
    assert Deadline(-5).left() == 0.5
    assert 9 < Deadline(10).left() <= 10


def test_a_deadline_waits_for_the_shorter_of_its_time_left_and_the_seconds_given():
    started = time.monotonic()
    assert Deadline(0.6).wait(lambda: False, 30) is False
    assert Deadline(30).wait(lambda: False, 0.1) is False
    assert time.monotonic() - started < 2
    assert Deadline(30).wait(lambda: True, gave_up=lambda: True) is True
