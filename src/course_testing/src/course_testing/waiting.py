"""Waiting for a condition instead of sleeping."""
import time


def wait_until(condition, timeout, what='the condition', poll=0.01):
    """Poll condition() until it returns a true value and return that value.

    Raises AssertionError naming `what` when timeout seconds pass first, so a test fails with a
    sentence rather than hanging or passing by luck.
    """
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError('timed out after %.1f s waiting for %s' % (timeout, what))
        time.sleep(poll)

