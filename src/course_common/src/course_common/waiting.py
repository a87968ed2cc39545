"""Waiting for a condition instead of sleeping: poll_until, the one deadline loop; wait_until, which
fails with a sentence (the tests); wait_for and Deadline, whose time-out is an answer (the checks that
judge a student's node); wait_in_slices, a timed wait that counts only the waiter's own time; and
measurement_window, the fixed window that a rate is counted over."""
import math
import time


def poll_until(condition, timeout, poll=0.01):
    """Poll condition() until it returns a true value or timeout seconds pass; return its last
    value (false on time-out). The one deadline loop: wait_until asserts on it, wait_for takes
    its answer as it is."""
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


def wait_in_slices(wait, seconds, slice_seconds=0.05):
    """Whether wait(s) (a timed wait answering whether what it waits for came within s seconds, as
    threading.Event.wait) answers True within `seconds` of the waiter's own time (rounded up to
    whole slices). The wait is made in slices, each counted as long as it was asked: a slice that
    ends later than asked (the waiter kept from the processor, most likely with the rest of the
    machine: a paused virtual machine, a host swapping) costs no more than asked, so what the
    waiter waits for gets its `seconds` of a running machine after all."""
    for _ in range(max(1, math.ceil(seconds / slice_seconds - 1e-9))):
        if wait(min(slice_seconds, seconds)):
            return True
    return False


def measurement_window(seconds, start=None):
    """Let a fixed window of `seconds` pass (from `start`, a time.monotonic(), or from now) while
    subscribers record: the window a rate or a speed is counted over, not a wait for something to
    happen. Returns the time.monotonic() at which the window ended."""
    start = time.monotonic() if start is None else start
    remaining = start + seconds - time.monotonic()
    if remaining > 0:
        time.sleep(remaining)
    return time.monotonic()


class Deadline:
    """The end of a run that may last `seconds` of wall time; its waits look every `poll` seconds."""

    def __init__(self, seconds, poll=0.05):
        self.end = time.monotonic() + seconds
        self.poll = poll

    def left(self, at_least=0.5):
        return max(at_least, self.end - time.monotonic())

    def wait(self, condition, seconds=None, gave_up=None, poll=None):
        """wait_for condition() within the time left (and `seconds` at most, when given)."""
        return wait_for(condition, self.left() if seconds is None else min(seconds, self.left()), gave_up,
                        self.poll if poll is None else poll)


def wait_for(condition, seconds, gave_up=None, poll=0.05):
    """Whether condition() holds within `seconds`; False on time-out, or as soon as gave_up()
    (say: the node ended, nothing more will come from it)."""
    poll_until(lambda: condition() or (gave_up is not None and gave_up()), seconds, poll)
    return bool(condition())
