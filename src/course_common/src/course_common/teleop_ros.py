"""The ROS side the keyboard teleops share (this module, unlike the rest of course_common, needs rospy)."""
import time

import rospy
from geometry_msgs.msg import Twist


def twist(linear, angular):
    """A Twist moving forward at `linear` m/s while turning at `angular` rad/s."""
    message = Twist()
    message.linear.x = linear
    message.angular.z = angular
    return message


def stop_robot_on_shutdown(publisher, flush_seconds):
    """On every way out (Ctrl-C, a closed terminal, SIGINT from roslaunch or rosnode), publish a zero
    Twist: a robot or relay keeps the last command it got and would drive on without one."""
    def stop_robot():
        publisher.publish(Twist())
        # publish() only queues the message for a sender thread that shutdown closes, and rospy
        # has no flush to wait on: give that thread one publishing period to deliver it.
        time.sleep(flush_seconds)
    rospy.on_shutdown(stop_robot)
