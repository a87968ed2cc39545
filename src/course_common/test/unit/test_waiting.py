import itertools
import time

import pytest

from course_common.waiting import measurement_window, wait_until


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
