#!/usr/bin/env python3
import rospy
from sensor_msgs.msg import LaserScan


def callback(msg):
    print('=====')
    for label, index in (('s1 [0]', 0), ('s2 [90]', 90), ('s3 [180]', 180), ('s4 [270]', 270), ('s5 [359]', 359)):
        print(label)
        print(msg.ranges[index])


rospy.init_node('laser_data')
sub = rospy.Subscriber('scan', LaserScan, callback)
rospy.spin()
