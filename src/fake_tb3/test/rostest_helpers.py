"""For the rostests: record what arrives on topics (with the wall time of arrival), look up TF."""
import threading
import time

import rospy
import tf2_ros


class Recorder:
    """Keeps (arrival wall time, message) of every message on `topic`."""

    def __init__(self, topic, message_type):
        self.lock = threading.Lock()
        self.messages = []
        self.subscriber = rospy.Subscriber(topic, message_type, self._on_message, queue_size=1000)

    def _on_message(self, message):
        with self.lock:
            self.messages.append((time.monotonic(), message))

    def latest(self):
        with self.lock:
            return self.messages[-1][1] if self.messages else None

    def since(self, wall_time):
        with self.lock:
            return [(t, m) for t, m in self.messages if t >= wall_time]

    def rate(self, start, end):
        """Messages per wall second between wall times start and end, from first to last arrival."""
        arrivals = [t for t, _ in self.since(start) if t <= end]
        return (len(arrivals) - 1) / (arrivals[-1] - arrivals[0]) if len(arrivals) > 1 else 0.0

    def stamp_rate(self, start_stamp, end_stamp):
        """Messages per second of header stamps: those stamped in [start, end), over end - start."""
        with self.lock:
            count = sum(1 for _, m in self.messages if start_stamp <= m.header.stamp < end_stamp)
        return count / (end_stamp - start_stamp).to_sec()


def rosout_lines(recorder, text):
    """The /rosout messages (a Recorder of rosgraph_msgs/Log) that contain `text`."""
    with recorder.lock:
        return [m.msg for _, m in recorder.messages if text in m.msg]


def lookup(tf_buffer, parent, child):
    """The latest transform parent -> child (geometry_msgs/Transform), or None while unknown."""
    try:
        return tf_buffer.lookup_transform(parent, child, rospy.Time(0)).transform
    except (tf2_ros.LookupException, tf2_ros.ExtrapolationException, tf2_ros.ConnectivityException):
        return None
