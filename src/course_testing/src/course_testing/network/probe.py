#!/usr/bin/env python3
"""Subscribe to TOPIC (any type, learnt from its publisher) and print one JSON line per message:
{"t": arrival time (CLOCK_MONOTONIC), "nan": true if any float in it is NaN, "values": {FIELD: value}}.

    probe.py TOPIC [FIELD ...]      FIELD is a dotted path to a number, e.g. pose.pose.position.x

Infinity is not NaN: a LaserScan reports "no return" as +inf (REP 117), which is correct.
"""
import json
import math
import sys
import time

import rosgraph
import rospy
import rostopic

from course_common.waiting import wait_until

MASTER_TIMEOUT = 60.0


def contains_nan(value):
    if isinstance(value, float):
        return math.isnan(value)
    if isinstance(value, (list, tuple)):
        return any(contains_nan(item) for item in value)
    if hasattr(value, '__slots__'):
        return any(contains_nan(getattr(value, slot)) for slot in value.__slots__)
    return False


def field(message, path):
    for name in path.split('.'):
        message = getattr(message, name)
    return message


def main():
    topic, fields = sys.argv[1], sys.argv[2:]
    # Started beside a master that may not be up yet (in another network namespace, say).
    wait_until(rosgraph.is_master_online, MASTER_TIMEOUT, 'the master of ROS_MASTER_URI', poll=0.1)
    rospy.init_node('probe', anonymous=True, disable_signals=True)
    message_class, resolved, _ = rostopic.get_topic_class(topic, blocking=True)

    def report(message):
        record = {'t': time.monotonic(), 'nan': contains_nan(message),
                  'values': {path: field(message, path) for path in fields}}
        # NaN is not JSON: a NaN value shows as null (and "nan" is true).
        record['values'] = {path: (None if isinstance(value, float) and math.isnan(value) else value)
                            for path, value in record['values'].items()}
        sys.stdout.write(json.dumps(record) + '\n')
        sys.stdout.flush()

    rospy.Subscriber(resolved, message_class, report, queue_size=100)
    try:
        rospy.spin()
    except KeyboardInterrupt:
        pass


if __name__ == '__main__':
    main()
