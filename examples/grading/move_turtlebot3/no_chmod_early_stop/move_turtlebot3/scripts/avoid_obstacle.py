#!/usr/bin/env python3
import rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist


def callback(msg):
    print(msg.ranges[0])
    if msg.ranges[0] > 1.0:      # the slide's comment says 1 meter, the slide's goal says 0.5 m
        move.linear.x = 0.5
    else:
        move.linear.x = 0.0
    pub.publish(move)


rospy.init_node('obstacle_avoidance')
pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
move = Twist()
sub = rospy.Subscriber('/scan', LaserScan, callback)
rospy.spin()
