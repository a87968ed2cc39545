#!/usr/bin/env python3
"""Exercise 1's publisher as students often write it: it sleeps ~sleep (simulated) seconds, 1 unless
given, before it publishes, for its subscribers to connect, then sends the digits of ~id at ~rate Hz
on ZabirovaKostyukova."""
import rospy
from std_msgs.msg import Int32

rospy.init_node('publisher_sleeping_first')
digits, rate = str(rospy.get_param('~id')), rospy.get_param('~rate')
first_sleep = rospy.get_param('~sleep', 1.0)
publisher = rospy.Publisher('ZabirovaKostyukova', Int32, queue_size=1000)
try:
    rospy.sleep(first_sleep)
    loop, sent = rospy.Rate(rate), 0
    while not rospy.is_shutdown():
        publisher.publish(Int32(int(digits[sent % len(digits)])))
        sent += 1
        loop.sleep()
except rospy.ROSInterruptException:   # stopped while it slept
    pass
