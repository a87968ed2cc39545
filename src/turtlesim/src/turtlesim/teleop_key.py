"""turtle_teleop_key: drive turtle1 with the arrow keys, one velocity command per key press.

Node teleop_turtle publishes turtle1/cmd_vel; the params scale_linear and scale_angular (default 2.0)
are read from the node's namespace, as the original does. Keys arrive one byte at a time, so an
arrow key (ESC [ A) acts on its last byte, and the capital letters A-D act alone too.
"""
import math
import sys

import rospy
from geometry_msgs.msg import Twist

from course_common.keyboard import teleop_keys, write_line

# last byte of each arrow key -> (linear, angular) before scaling
KEY_MOTIONS = {'A': (1.0, 0.0), 'B': (-1.0, 0.0), 'C': (0.0, -1.0), 'D': (0.0, 1.0)}
QUIT_KEYS = ('q', '\x03')  # 'q', or Ctrl-C (raw mode delivers it as a byte)
BANNER = ('Reading from keyboard\n'
          '---------------------------\n'
          "Use arrow keys to move the turtle. 'q' to quit.")


def read_scale(name):
    value = rospy.get_param(name, 2.0)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError('Parameter %s must be a finite number, not %r' % (rospy.resolve_name(name), value))
    return float(value)


def main():
    rospy.init_node('teleop_turtle')
    try:
        scale_linear, scale_angular = read_scale('scale_linear'), read_scale('scale_angular')
    except ValueError as error:
        print(error, file=sys.stderr)
        sys.exit(1)
    publisher = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
    with teleop_keys('turtle_teleop_key') as keys:
        write_line(BANNER)
        while not rospy.is_shutdown():
            key = keys.read(timeout=0.1)
            if key in QUIT_KEYS:
                break
            if key in KEY_MOTIONS:
                linear, angular = KEY_MOTIONS[key]
                command = Twist()
                command.linear.x, command.angular.z = scale_linear * linear, scale_angular * angular
                publisher.publish(command)
    # No stop command on the way out, as in the original: turtlesim stops a turtle by itself 1 s
    # after its last command.
    rospy.signal_shutdown('quit')
