"""The one way to record a topic: every message with the time it arrived, and waits on what came."""
import threading
import time

import rospy

from course_common.waiting import wait_until

MAX_MESSAGES = 100000   # kept in memory at most: a topic flooded without end stays within it
QUEUE_SIZE = 1000       # messages rospy holds for the recorder while its thread waits


class TopicRecorder:
    """The messages of one topic, each with the time.monotonic() it arrived, for the checks and the
    tests to wait on and to measure afterwards. Past MAX_MESSAGES the older half is dropped;
    messages are numbered from the first that arrived all the same."""

    def __init__(self, topic, message_type):
        self._lock = threading.Lock()
        self._entries = []  # (arrival time.monotonic(), message)
        self._dropped = 0   # how many of the first messages are no longer kept
        self.subscriber = rospy.Subscriber(topic, message_type, self._keep, queue_size=QUEUE_SIZE)

    def _keep(self, message):
        with self._lock:
            self._entries.append((time.monotonic(), message))
            if len(self._entries) > MAX_MESSAGES:
                half = len(self._entries) // 2
                del self._entries[:half]
                self._dropped += half

    def count(self):
        """How many messages have arrived."""
        with self._lock:
            return self._dropped + len(self._entries)

    def entries(self, start=0):
        """(arrival time, message) of the messages from the start-th on (of those kept)."""
        with self._lock:
            return self._entries[max(0, start - self._dropped):]

    def messages(self, start=0):
        """The messages from the start-th on (of those kept)."""
        return [message for _, message in self.entries(start)]

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
        """Forget every message: the next one is the first."""
        with self._lock:
            self._entries.clear()
            self._dropped = 0

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
        """Unsubscribe: nothing more is recorded."""
        self.subscriber.unregister()
