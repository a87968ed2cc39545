#!/usr/bin/env python3
# Right behaviour, but it catches Ctrl-C and keeps going: it never stops on its own.
import signal
import time

import rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist


def callback(msg):
    move = Twist()
    move.linear.x = 0.5 if msg.ranges[0] > 0.5 else 0.0
    pub.publish(move)


rospy.init_node('obstacle_avoidance', disable_signals=True)
signal.signal(signal.SIGINT, signal.SIG_IGN)
pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
sub = rospy.Subscriber('/scan', LaserScan, callback)
while True:
    time.sleep(1)
