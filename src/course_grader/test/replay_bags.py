"""Runs as the grader keeps them (course_grader.bags: the same topics, written by bags.write_bag),
made up for the replay's tests: no simulator, no master."""
import math
import os

import rospy
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
from turtlesim.msg import Pose
from turtlesim.srv import SetPenRequest

from course_grader import bags

START = 40.0          # simulated s of the runs' first message
TB3_STOP = 6.0        # the robot drives at TB3_SPEED until then (s after START), then stands
TB3_SPEED = 0.2
TB3_SPAWN = (-2.0, -0.5)
CIRCLE_SECONDS = 2 * math.pi   # turtle1 turns at 1 rad/s: the circle closes then
TICK = 0.016


def _at(seconds):
    return rospy.Time.from_sec(START + seconds)


def tb3_messages(seconds=10.0, speed=TB3_SPEED, stop=TB3_STOP, scans=True):
    """fake_tb3 in turtlebot3_world: the burger drives straight from TB3_SPAWN until `stop` s,
    odometry at 30 Hz, scans at 5 Hz (a wall 1 m around it)."""
    messages = [('/fake_tb3/run', String('{"model": "burger", "world": "turtlebot3_world"}'), _at(0), None)]
    for index in range(int(seconds * 30) + 1):
        t = index / 30.0
        odom = Odometry()
        odom.pose.pose.position.x = TB3_SPAWN[0] + speed * min(t, stop)
        odom.pose.pose.position.y = TB3_SPAWN[1]
        odom.pose.pose.orientation.w = 1.0
        odom.twist.twist.linear.x = speed if t < stop else 0.0
        messages.append(('/odom', odom, _at(t), None))
        if scans and index % 6 == 0:
            scan = LaserScan(angle_min=0.0, angle_increment=2 * math.pi / 360, range_min=0.12, range_max=3.5,
                             ranges=[1.0] * 360)
            messages.append(('/scan', scan, _at(t), None))
    return messages


def turtlesim_messages(seconds=8.0):
    """turtle1 on a circle of 2 m at 1 rad/s from (5.5, 3.5), a pose every tick; its pen red, 4
    wide, from the start."""
    messages = [('/turtlesim/canvas', String('{"background": [69, 86, 255]}'), _at(0), None),
                ('/turtlesim/turtles', String('{"names": ["turtle1"]}'), _at(0), None),
                ('/turtle1/pen', SetPenRequest(255, 0, 0, 4, 0), _at(0), None)]
    for index in range(int(seconds / TICK) + 1):
        t = index * TICK
        pose = Pose(x=5.5 + 2 * math.sin(t), y=3.5 + 2 * (1 - math.cos(t)), theta=t, linear_velocity=2.0,
                    angular_velocity=1.0)
        messages.append(('/turtle1/pose', pose, _at(t), None))
    return messages


def write_run(folder, run, messages, marks):
    """<run>.bag and <run>.marks.json in folder, as the grader writes them."""
    os.makedirs(folder, exist_ok=True)
    bags.write_bag(os.path.join(folder, run + bags.BAG_SUFFIX), messages)
    bags.write_marks(os.path.join(folder, run + bags.MARKS_SUFFIX), marks)


def write_class(out_dir):
    """alice's two runs in out_dir/alice: avoid_obstacle (its stop marked) and circle (its closure)."""
    folder = os.path.join(out_dir, 'alice')
    write_run(folder, 'avoid_obstacle', tb3_messages(),
              [bags.mark(START + TB3_STOP, 'stopped after 1.20 m: front beam 0.42 m', 'avoid_stops')])
    write_run(folder, 'circle', turtlesim_messages(),
              [bags.mark(START + CIRCLE_SECONDS, 'a full turn driven: the circle closes', 'circle')])
    return folder
