"""The one way to record a topic: every message with the time it arrived, and waits on what came."""
import math
import threading
import time

import rospy

from course_common.waiting import wait_until


class TopicRecorder:
    """Every message of one topic, with the time.monotonic() it arrived, for a test, a benchmark or
    the tour to wait on and to measure afterwards."""

    def __init__(self, topic, message_type, queue_size=1000):
        self._lock = threading.Lock()
        self._entries = []  # (arrival time.monotonic(), message)
        self.subscriber = rospy.Subscriber(topic, message_type, self._keep, queue_size=queue_size)

    def _keep(self, message):
        with self._lock:
            self._entries.append((time.monotonic(), message))

    def count(self):
        with self._lock:
            return len(self._entries)

    def entries(self, start=0):
        """(arrival time, message) of the messages from the start-th on."""
        with self._lock:
            return self._entries[start:]

    def messages(self, start=0):
        """The messages from the start-th on."""
        with self._lock:
            return [message for _, message in self._entries[start:]]

    def latest(self):
        """The newest message, or None before the first."""
        with self._lock:
            return self._entries[-1][1] if self._entries else None

    def arrived_since(self, wall_time):
        """(arrival time, message) of the messages that arrived at or after time.monotonic() `wall_time`."""
        with self._lock:
            return [(arrival, message) for arrival, message in self._entries if arrival >= wall_time]

    def rate(self, start, end):
        """Messages per wall second between time.monotonic() start and end, first to last arrival."""
        arrivals = [arrival for arrival, _ in self.arrived_since(start) if arrival <= end]
        return (len(arrivals) - 1) / (arrivals[-1] - arrivals[0]) if len(arrivals) > 1 else 0.0

    def clear(self):
        with self._lock:
            self._entries.clear()

    def wait_for_count(self, count, timeout=30.0):
        """Wait until `count` messages have arrived in all."""
        wait_until(lambda: self.count() >= count, timeout, '%d messages on %s' % (count, self.subscriber.name))

    def next_message(self, timeout=5.0):
        """The first message that arrives after this call."""
        start = self.count()
        wait_until(lambda: self.count() > start, timeout, 'a message on %s' % self.subscriber.name)
        return self.messages(start)[0]

    def wait_for(self, condition, timeout, what):
        """Wait until condition(newest message) holds; returns that message."""
        def holds():
            message = self.latest()
            return message is not None and condition(message) and message
        return wait_until(holds, timeout, what)

    def record(self, seconds):
        """(arrival time, message) of the messages that arrive over the next `seconds` seconds, from
        the first of them to the first `seconds` after it."""
        first = self.count()

        def long_enough():
            entries = self.entries(first)
            return len(entries) > 1 and entries[-1][0] - entries[0][0] >= seconds
        wait_until(long_enough, seconds + 10, 'messages on %s over %.1f s' % (self.subscriber.name, seconds))
        return self.entries(first)

    def close(self):
        self.subscriber.unregister()


def path_length(points):
    """Length in metres of the polyline through (x, y) points."""
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(points, points[1:]))
