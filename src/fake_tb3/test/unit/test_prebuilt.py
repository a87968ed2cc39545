"""Prebuilt messages: the bytes they send are genpy's, byte for byte, whatever the values."""
import io
import math

import numpy as np
import pytest
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage

from fake_tb3.prebuilt import prebuilt


def genpy_bytes(message):
    buffer = io.BytesIO()
    message.serialize(buffer)
    return buffer.getvalue()


def test_odometry_bytes_are_genpys_for_any_values():
    odom = Odometry()
    odom.header.frame_id, odom.child_frame_id = 'tb3_0/odom', 'tb3_0/base_footprint'
    odom.pose.covariance = [float(i) for i in range(36)]
    fast = prebuilt(odom, [('header.stamp.secs', 'I'), ('header.stamp.nsecs', 'I'),
                           ('pose.pose.position.x', 'd'), ('twist.twist.angular.z', 'd')])
    assert isinstance(fast, Odometry) and fast._md5sum == Odometry._md5sum
    random = np.random.default_rng(1)
    for secs, nsecs, x, turn in [(0, 0, 0.0, 0.0), (12, 999999999, -2.5, math.inf),
                                 (4294967295, 1, 1e308, -0.0)] + [
            (int(random.integers(0, 2 ** 32)), int(random.integers(0, 10 ** 9)),
             float(random.normal()), float(random.normal())) for _ in range(20)]:
        fast.update(secs, nsecs, x, turn)
        fast.header.seq = secs % 1000  # rospy sets it before serialising
        odom.header.stamp.secs, odom.header.stamp.nsecs, odom.header.seq = secs, nsecs, secs % 1000
        odom.pose.pose.position.x, odom.twist.twist.angular.z = x, turn
        assert genpy_bytes(fast) == genpy_bytes(odom)


def test_scan_ranges_and_a_transform_in_an_array():
    scan = LaserScan(angle_max=6.28319, range_min=0.12, range_max=3.5, ranges=[0.0] * 360,
                     intensities=[0.0] * 360)
    scan.header.frame_id = 'base_scan'
    fast = prebuilt(scan, [('header.stamp.nsecs', 'I')], array=('ranges', 360))
    ranges = np.where(np.arange(360) % 7 == 0, np.inf, np.linspace(0.12, 3.5, 360))
    fast.update(5)
    fast.write_array(ranges)
    scan.header.stamp.nsecs, scan.ranges = 5, ranges.tolist()
    assert genpy_bytes(fast) == genpy_bytes(scan)
    transform = TransformStamped()
    transform.header.frame_id, transform.child_frame_id = 'odom', 'base_footprint'
    tf = TFMessage([transform])
    fast_tf = prebuilt(tf, [('transforms.0.transform.translation.y', 'd')])
    fast_tf.update(-0.5)
    transform.transform.translation.y = -0.5
    assert genpy_bytes(fast_tf) == genpy_bytes(tf)
    clock = prebuilt(Clock(), [('clock.secs', 'I'), ('clock.nsecs', 'I')])
    clock.update(3, 250000000)
    assert genpy_bytes(clock) == genpy_bytes(Clock(clock=Clock().clock.__class__(3, 250000000)))


def test_a_field_that_cannot_be_found_is_refused():
    with pytest.raises(AttributeError):
        prebuilt(Clock(), [('clock.minutes', 'I')])
