#!/usr/bin/env python3
# Sleeps before it starts its node (as if it waited for something that never comes).
import time
import rospy
from geometry_msgs.msg import Twist

time.sleep(10 ** 6)
rospy.init_node('vel_publisher')
pub = rospy.Publisher('cmd_vel', Twist, queue_size=10)
rate = rospy.Rate(1)
while not rospy.is_shutdown():
    pub.publish(Twist())
    rate.sleep()
