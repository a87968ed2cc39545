#! /usr/bin/env python

import rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist

def callback(msg):         # Define a function called 'callback' that receives a parameter named 'msg'
    print('==========')
    print('s1 [270]')      #value right-direction laser beam
    print msg.ranges[270]
    print('s2 [0]')        #value front-direction laser beam
    print msg.ranges[0]
    print('s3 [90]')       #value left-direction laser beam
    print msg.ranges[90]
    #If the distance to an obstacle in front of the robot is bigger than 1 meter, the robot will move forward
    if msg.ranges[0] > 0.5:
      move.linear.x = 0.5
      move.angular.z = 0.0
    else:
      move.linear.x = 0.0
      move.angular.z = 0.0
    pub.publish(move)

rospy.init_node('obstacle_avoidance')                  # Initiate a Node called 'obstacle avoidance'
sub = rospy.Subscriber('/scan', LaserScan, callback)   # Create a Subscriber to the /scan topic
pub = rospy.Publisher('/cmd_vel', Twist)               #Create a publisher on the /cmd_vel topic
move = Twist()
rospy.spin()
