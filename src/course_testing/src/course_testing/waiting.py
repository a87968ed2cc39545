"""Waiting for a condition instead of sleeping, and the fixed windows that measurements count over."""
import time


def poll_until(condition, timeout, poll=0.01):
    """Poll condition() until it returns a true value or timeout seconds pass; return its last
    value (false on time-out). The one deadline loop: wait_until asserts on it, the checks that
    judge a student's node (course_checks.waiting) take its answer as it is."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value or time.monotonic() > deadline:
            return value
        time.sleep(poll)


def wait_until(condition, timeout, what='the condition', poll=0.01):
    """Poll condition() until it returns a true value and return that value.

    Raises AssertionError naming `what` when timeout seconds pass first, so a test fails with a
    sentence rather than hanging or passing by luck.
    """
    value = poll_until(condition, timeout, poll)
    if not value:
        raise AssertionError('timed out after %.1f s waiting for %s' % (timeout, what))
    return value


def measurement_window(seconds, start=None):
    """Let a fixed window of `seconds` pass (from `start`, a time.monotonic(), or from now) while
    subscribers record: the window a rate or a speed is counted over, not a wait for something to
    happen. Returns the time.monotonic() at which the window ended."""
    start = time.monotonic() if start is None else start
    remaining = start + seconds - time.monotonic()
    if remaining > 0:
        time.sleep(remaining)
    return time.monotonic()
