#!/usr/bin/env python3
"""Exercise 1's publisher timed by the wall clock (as with ros::WallRate, or a sleep of the
language's own): it sends the digits of ~id at ~rate Hz of wall time on ZabirovaKostyukova,
whatever /clock says."""
import time

import rospy
from std_msgs.msg import Int32

rospy.init_node('publisher_on_the_wall_clock')
digits, rate = str(rospy.get_param('~id')), rospy.get_param('~rate')
publisher = rospy.Publisher('ZabirovaKostyukova', Int32, queue_size=1000)
sent, start = 0, time.monotonic()
while not rospy.is_shutdown():
    publisher.publish(Int32(int(digits[sent % len(digits)])))
    sent += 1
    time.sleep(max(0.0, start + sent / rate - time.monotonic()))   # a schedule, as ros::WallRate keeps
