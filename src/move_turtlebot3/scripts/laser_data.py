#!/usr/bin/env python3
# Prints five beams of every laser scan: front (0), left (90), back (180), right (270), 359.
import rospy
from sensor_msgs.msg import LaserScan


def beam(msg, index):
    # A scan can hold fewer beams than the LDS-01's 360 (another laser, a broken message): say so
    # instead of dying on an IndexError. inf (nothing within range_max) and nan (no valid reading)
    # are what the laser reported, so they are printed as they are.
    if index < len(msg.ranges):
        return msg.ranges[index]
    return 'no beam %d (the scan has %d)' % (index, len(msg.ranges))


def callback(msg):           # called with every message that arrives on 'scan'
    print('==========')
    print('s1 [0]')          # beam 0 looks straight ahead
    print(beam(msg, 0))      # distance in metres to what is in front of the robot
    print('s2 [90]')         # left
    print(beam(msg, 90))
    print('s3 [180]')        # behind
    print(beam(msg, 180))
    print('s4 [270]')        # right
    print(beam(msg, 270))
    print('s5 [359]')        # the last beam, one degree right of the front
    print(beam(msg, 359))


rospy.init_node('laser_data')                        # this node is called 'laser_data'
sub = rospy.Subscriber('scan', LaserScan, callback)  # the laser publishes on 'scan'
rospy.spin()
