"""The simulators' request queue: ROS callbacks ask, the simulation's own thread does.

A simulator (turtlesim, fake_tb3) steps its world in one thread. Its ROS callbacks (a cmd_vel, a
service call) run in rospy's threads and never touch the world: they submit() an action, which the
simulation thread runs with run_pending() between two ticks, in the order submitted. A service
waits for its action with call() and gets its result, or the error it raised.
"""
import collections
import threading


class Stopped(RuntimeError):
    """The simulator stopped before it ran the action."""


class Request:
    """An action waiting for the simulation thread; the caller may wait for its result."""
    __slots__ = ('action', 'waited', 'done', 'result', 'error')

    def __init__(self, action, waited):
        self.action = action
        self.waited = waited  # False: nobody reads the result, so an error goes to on_error
        self.done = threading.Event()
        self.result = None
        self.error = None


class RequestQueue:
    """Actions for the simulation thread.

    expected: the exception types an action may raise as a refusal (their text is for the user);
    any other exception is a bug and propagates out of run_pending(). on_error(error) hears the
    refusals of actions nobody waits for (a bad cmd_vel)."""

    def __init__(self, expected=(), on_error=None):
        self._queue = collections.deque()  # append and popleft are atomic: no lock needed
        self._expected = tuple(expected)
        self._on_error = on_error

    def submit(self, action, waited=False):
        """Queue action(*args of run_pending) for the simulation thread; returns the Request."""
        request = Request(action, waited)
        self._queue.append(request)
        return request

    def call(self, action, stopped, poll=0.1):
        """Queue the action, wait until the simulation thread has run it and return its result,
        or raise the refusal it raised. Raises Stopped once stopped() is true and nothing ran it."""
        request = self.submit(action, waited=True)
        while not request.done.wait(poll):
            if stopped():
                raise Stopped('the simulator is shutting down')
        if request.error is not None:
            raise request.error
        return request.result

    def run_pending(self, *args):
        """In the simulation thread: run every queued action, oldest first, with these arguments."""
        queue = self._queue
        while queue:
            request = queue.popleft()
            try:
                request.result = request.action(*args)
            except self._expected as error:
                request.error = error
                if not request.waited and self._on_error is not None:
                    self._on_error(error)
            finally:
                request.done.set()

    def fail_pending(self, error):
        """Give every queued request this error (the simulation thread is stopping)."""
        while self._queue:
            request = self._queue.popleft()
            request.error = error
            request.done.set()

    def __len__(self):
        return len(self._queue)
