#!/usr/bin/env python3
# The slide's "baby step" of obstacle avoidance: drive forward, stop when something is closer than
# 0.5 m straight ahead.
import rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist


def beam(msg, index):
    # A scan with fewer beams than expected has no reading here: None, so that it is printed and
    # never taken for a free way.
    return msg.ranges[index] if index < len(msg.ranges) else None


def callback(msg):           # called with every scan
    print('==========')
    print('s1 [270]')        # right
    print(beam(msg, 270))
    print('s2 [0]')          # front: beam 0 looks straight ahead
    print(beam(msg, 0))
    print('s3 [90]')         # left
    print(beam(msg, 90))
    front = beam(msg, 0)
    # Forward only when the front reading is a number above 0.5 m. inf (nothing within range) is
    # above it, so the robot drives on; nan, -inf (too close to measure) and a missing beam are
    # not, so the robot stops rather than drive on a reading it cannot trust.
    if front is not None and front > 0.5:
        move.linear.x = 0.5
        move.angular.z = 0.0
    else:
        move.linear.x = 0.0
        move.angular.z = 0.0
    pub.publish(move)


rospy.init_node('obstacle_avoidance')                     # this node is called 'obstacle_avoidance'
pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)   # the robot's velocity commands
move = Twist()
# Subscribe last: the callback uses pub and move, and a scan can arrive as soon as we subscribe.
sub = rospy.Subscriber('/scan', LaserScan, callback)      # the laser scans
rospy.spin()
