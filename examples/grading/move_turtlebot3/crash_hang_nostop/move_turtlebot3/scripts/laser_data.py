#!/usr/bin/env python3
import rospy
from sensor_msgs.msg import LaserScan


def callback(msg):
    print('==========')
    print('s1 [0]')
    print(msg.range[0])


rospy.init_node('laser_data')
sub = rospy.Subscriber('scan', LaserScan, callback)
rospy.spin()
