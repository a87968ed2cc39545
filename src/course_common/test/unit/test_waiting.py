import itertools
import threading
import time

import pytest

from course_common.waiting import measurement_window, wait_in_slices, wait_until


def test_wait_until_returns_the_first_true_value():
    counter = itertools.count()
    assert wait_until(lambda: next(counter) >= 3 and 'done', timeout=1.0) == 'done'


def test_wait_until_fails_with_what_it_waited_for():
    with pytest.raises(AssertionError, match='timed out after 0.1 s waiting for the moon'):
        wait_until(lambda: False, timeout=0.1, what='the moon')


def test_a_measurement_window_lasts_its_length_from_its_start(monkeypatch):
    start = time.monotonic()
    end = measurement_window(0.2, start)
    assert end - start >= 0.2
    slept = []
    monkeypatch.setattr(time, 'sleep', slept.append)
    measurement_window(5.0, time.monotonic() - 4.0)  # only what is left of the window
    assert 0.9 < slept[0] <= 1.0
    measurement_window(5.0, time.monotonic() - 6.0)  # a window already over ends at once
    assert len(slept) == 1


def test_a_wait_in_slices_counts_each_slice_as_long_as_it_was_asked():
    asked = []

    def nothing_comes(seconds):
        asked.append(seconds)
        return False
    assert wait_in_slices(nothing_comes, 3.0) is False
    assert asked == [0.05] * 60   # however long each took: a slice the machine paused counts 0.05 s


def test_a_wait_in_slices_ends_when_what_it_waits_for_comes():
    answers = iter([False, False, True])
    asked = []

    def comes_in_the_third(seconds):
        asked.append(seconds)
        return next(answers)
    assert wait_in_slices(comes_in_the_third, 3.0) is True and len(asked) == 3
    assert wait_in_slices(lambda seconds: asked.append(seconds), 0.01) is False and asked[-1] == 0.01


def test_a_wait_in_slices_on_an_event_lasts_its_seconds_when_nothing_comes():
    start = time.monotonic()
    assert wait_in_slices(threading.Event().wait, 0.2) is False
    assert time.monotonic() - start >= 0.2
