#! /usr/bin/env python
import rospy
from sensor_msgs.msg import LaserScan

def callback(msg):            # Define a function called 'callback' that receives a parameter named 'msg'
    print('==========')
    print('s1 [0]')           #value front-direction laser beam
    print msg.ranges[0]       # print the distance to an obstacle in front of the robot
    print('s2 [90]')
    print msg.ranges[90]
    print('s3 [180]')
    print msg.ranges[180]
    print('s4 [270]')
    print msg.ranges[270]
    print('s5 [359]')
    print msg.ranges[359]

rospy.init_node('laser_data')                          # Initiate a Node called 'laser_data'
sub = rospy.Subscriber('scan', LaserScan, callback)    # Create a Subscriber to the laser/scan topci
rospy.spin()
