"""Waiting for what a node does, within the time a run has left: False on time-out, not an error."""
import time

from course_testing.waiting import poll_until


class Deadline:
    """The end of a run that may last `seconds` of wall time."""

    def __init__(self, seconds):
        self.end = time.monotonic() + seconds

    def left(self, at_least=0.5):
        return max(at_least, self.end - time.monotonic())

    def wait(self, condition, seconds=None, gave_up=None):
        """wait_for condition() within the time left (and `seconds` at most, when given)."""
        return wait_for(condition, self.left() if seconds is None else min(seconds, self.left()), gave_up)


def wait_for(condition, seconds, gave_up=None, poll=0.05):
    """Whether condition() holds within `seconds`; False on time-out, or as soon as gave_up()
    (say: the node ended, nothing more will come from it)."""
    poll_until(lambda: condition() or (gave_up is not None and gave_up()), seconds, poll)
    return bool(condition())
