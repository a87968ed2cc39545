import itertools

import pytest

from course_testing.waiting import wait_until


def test_wait_until_returns_the_first_true_value():
    counter = itertools.count()
    assert wait_until(lambda: next(counter) >= 3 and 'done', timeout=1.0) == 'done'


def test_wait_until_fails_with_what_it_waited_for():
    with pytest.raises(AssertionError, match='timed out after 0.1 s waiting for the moon'):
        wait_until(lambda: False, timeout=0.1, what='the moon')
