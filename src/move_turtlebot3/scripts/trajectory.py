#!/usr/bin/env python3
# Drives the TurtleBot3 in a circle: a constant forward speed and turn rate, sent once a second.
import rospy                            # the Python library for ROS
from geometry_msgs.msg import Twist     # the velocity message of geometry_msgs


def number_param(name, default):
    value = rospy.get_param(name, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        rospy.logfatal('%s must be a number, not %r' % (rospy.resolve_name(name), value))
        raise SystemExit(1)
    return float(value)


def talker():
    rospy.init_node('vel_publisher')                        # this node is called 'vel_publisher'
    pub = rospy.Publisher('cmd_vel', Twist, queue_size=10)  # the robot listens on cmd_vel
    move = Twist()                                          # the command we send, filled below
    move.linear.x = number_param('~linear', 1.0)            # m/s forward
    move.angular.z = number_param('~angular', 1.0)          # rad/s counter-clockwise
    rate = rospy.Rate(1)                                    # publish once per second (1 Hz)
    while not rospy.is_shutdown():
        pub.publish(move)
        rate.sleep()


if __name__ == '__main__':
    try:
        talker()
    except rospy.ROSInterruptException:
        pass
