"""The ROS side of the keyboard teleop: reads keys, publishes ~cmd_vel every 0.1 s pass."""
import time

import rospy
from geometry_msgs.msg import Twist

from course_common.keyboard import teleop_keys, write_line
from turtlebot_teleop.keys import BANNER, PASS_SECONDS, QUIT_KEY, KeyboardTeleop


def _twist(linear, angular):
    twist = Twist()
    twist.linear.x = linear
    twist.angular.z = angular
    return twist


def _stop_robot(publisher):
    """Send a zero Twist before quitting, or the relay would keep the last command forever."""
    publisher.publish(Twist())
    # publish() only queues the message for a sender thread that shutdown closes, and rospy has
    # no flush to wait on: give that thread one pass to deliver it.
    time.sleep(PASS_SECONDS)


def _drive(keys, teleop, publisher):
    """Passes until Ctrl-C, the end of the terminal or the node's shutdown."""
    while not rospy.is_shutdown():
        pass_end = time.monotonic() + PASS_SECONDS
        remaining = PASS_SECONDS
        while remaining > 0:
            key = keys.read(timeout=remaining)
            if key == QUIT_KEY:
                return
            if key is not None and teleop.press(key):
                write_line(teleop.speeds_line())
            remaining = pass_end - time.monotonic()
        publisher.publish(_twist(*teleop.end_pass()))


def main():
    teleop = KeyboardTeleop()
    with teleop_keys('turtlebot_teleop_key') as keys:
        rospy.init_node('turtlebot_teleop_keyboard')
        publisher = rospy.Publisher('~cmd_vel', Twist, queue_size=1)
        # Runs on every way out: Ctrl-C, closing or losing the terminal, SIGINT from roslaunch or rosnode.
        rospy.on_shutdown(lambda: _stop_robot(publisher))
        write_line(BANNER)
        write_line(teleop.speeds_line())
        _drive(keys, teleop, publisher)
    rospy.signal_shutdown('quit')
