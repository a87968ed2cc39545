#!/usr/bin/env python3
"""Publish geometry_msgs/Twist on TOPIC at RATE messages per second for SECONDS, then print
{"sent": n, "seconds": s, "subscribers": k} as JSON.

    flood.py TOPIC RATE SECONDS [VALUES]

VALUES cycles through Twists given as "linear.x,linear.y,angular.z;..." (nan and inf allowed);
default "1,0,1". It starts once a subscriber is connected (and fails if none comes). Publishing is synchronous (no queue), so `sent` counts messages handed to the
subscribers' sockets, not messages dropped from a queue: a slow subscriber slows the flood down and
shows up as a lower rate.
"""
import json
import sys
import time

import rospy
from geometry_msgs.msg import Twist

from course_common.waiting import wait_until

WAIT_FOR_SUBSCRIBER_SECONDS = 20.0


def twists(spec):
    messages = []
    for triple in spec.split(';'):
        linear_x, linear_y, angular_z = (float(number) for number in triple.split(','))
        message = Twist()
        message.linear.x, message.linear.y, message.angular.z = linear_x, linear_y, angular_z
        messages.append(message)
    return messages


def main():
    topic, rate, seconds = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    messages = twists(sys.argv[4] if len(sys.argv) > 4 else '1,0,1')
    rospy.init_node('flood', anonymous=True, disable_signals=True)
    publisher = rospy.Publisher(topic, Twist, queue_size=None)  # None: synchronous, see above
    wait_until(publisher.get_num_connections, WAIT_FOR_SUBSCRIBER_SECONDS, 'a subscriber to %s' % topic)

    sent = 0
    start = time.monotonic()
    while True:
        elapsed = time.monotonic() - start
        if elapsed >= seconds:
            break
        due = min(int(elapsed * rate) + 1, int(seconds * rate))
        while sent < due:
            publisher.publish(messages[sent % len(messages)])
            sent += 1
        time.sleep(0.0005)  # the schedule catches up in bursts of a few messages
    print(json.dumps({'sent': sent, 'seconds': time.monotonic() - start,
                      'subscribers': publisher.get_num_connections()}), flush=True)
    rospy.signal_shutdown('flood done')


if __name__ == '__main__':
    main()
