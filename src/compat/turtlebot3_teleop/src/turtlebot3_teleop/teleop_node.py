"""ROS side of the TurtleBot3 keyboard teleop: reads keys, publishes cmd_vel every 0.1 s."""
import time

import rospy
from geometry_msgs.msg import Twist

from course_common.keyboard import teleop_keys, write_line
from course_common.teleop_ros import stop_robot_on_shutdown, twist
from turtlebot3_teleop.key_commands import DEFAULT_MODEL, KeyCommands, speed_limits

PUBLISH_PERIOD = 0.1  # s, wall clock: the user types in real time even when the simulation runs faster


def drive(keys, commands, publisher):
    """Read keys until Ctrl-C (or the terminal closes), publishing the ramped command at every pass."""
    write_line(commands.banner())
    next_publish = time.monotonic()
    while not rospy.is_shutdown():
        key = keys.read(timeout=max(0.0, next_publish - time.monotonic()))
        if key is not None:
            text = commands.press(key)
            if commands.quit:
                return
            if text is not None:
                write_line(text)
        if time.monotonic() >= next_publish:
            publisher.publish(twist(*commands.ramp()))
            # Never catch up with a burst after a stall: the next pass is one period from now at most.
            next_publish = max(next_publish + PUBLISH_PERIOD, time.monotonic())


def main():
    rospy.init_node('turtlebot3_teleop_keyboard')
    model = rospy.get_param('model', DEFAULT_MODEL)
    max_linear, max_angular, known = speed_limits(model)
    if not known:
        rospy.logwarn('Unknown TurtleBot3 model "%s" (burger, waffle or waffle_pi): using the limits '
                      'of %s.', model, DEFAULT_MODEL)
    commands = KeyCommands(max_linear, max_angular)
    publisher = rospy.Publisher('cmd_vel', Twist, queue_size=10)
    stop_robot_on_shutdown(publisher, PUBLISH_PERIOD)
    with teleop_keys('turtlebot3_teleop_key') as keys:
        drive(keys, commands, publisher)
    rospy.signal_shutdown('quit')
