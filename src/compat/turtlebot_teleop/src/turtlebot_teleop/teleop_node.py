"""ROS side of the TurtleBot2 keyboard teleop: reads keys, publishes ~cmd_vel every 0.1 s pass."""
import time

import rospy
from geometry_msgs.msg import Twist

from course_common.keyboard import teleop_keys, write_line
from course_common.teleop_ros import stop_robot_on_shutdown, twist
from turtlebot_teleop.key_commands import BANNER, PASS_SECONDS, QUIT_KEY, KeyCommands


def _drive(keys, commands, publisher):
    """Passes until Ctrl-C, the end of the terminal or the node's shutdown."""
    while not rospy.is_shutdown():
        pass_end = time.monotonic() + PASS_SECONDS
        remaining = PASS_SECONDS
        while remaining > 0:
            key = keys.read(timeout=remaining)
            if key == QUIT_KEY:
                return
            if key is not None and commands.press(key):
                write_line(commands.speeds_line())
            remaining = pass_end - time.monotonic()
        publisher.publish(twist(*commands.end_pass()))


def main():
    commands = KeyCommands()
    with teleop_keys('turtlebot_teleop_key') as keys:
        rospy.init_node('turtlebot_teleop_keyboard')
        publisher = rospy.Publisher('~cmd_vel', Twist, queue_size=1)
        stop_robot_on_shutdown(publisher, PASS_SECONDS)
        write_line(BANNER)
        write_line(commands.speeds_line())
        _drive(keys, commands, publisher)
    rospy.signal_shutdown('quit')
