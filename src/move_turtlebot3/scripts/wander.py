#!/usr/bin/env python3
# The slide's real goal: make the robot move around avoiding obstacles. Unlike avoid_obstacle.py it
# looks at whole sectors of the scan instead of one beam, and instead of stopping it heads for the
# most open direction ahead, so it keeps exploring.
import math

import rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist

HEADINGS = [math.radians(d) for d in range(-90, 91, 10)]  # directions it may head for
WINDOW = math.radians(20)   # a direction is as free as the nearest beam within 20 degrees of it
STOP_DISTANCE = 0.45        # m: closer than this ahead, turn on the spot
SIDE_DISTANCE = 0.25        # m: steer away from anything this close beside
SLOW_DISTANCE = 1.0         # m: slow down when the way ahead is shorter than this
FAR_ENOUGH = 2.0            # m: directions free this far are all good, the straighter the better
SPEED = 0.22                # m/s: the burger's top speed
TURN_SPEED = 1.0            # rad/s
turn = 0.0                  # rad/s: the turn on the spot under way while blocked, 0 while driving


def beams(msg):
    # (angle, distance) of every beam, the angle computed from the scan itself so that a laser
    # with another number of beams is read correctly. Real scans hold inf (nothing within
    # range_max: free up to there), -inf (too close to measure: an obstacle at 0), and nan or
    # values under range_min (no valid reading): those are left out, neither free nor blocked.
    result = []
    for index, distance in enumerate(msg.ranges):
        if distance == math.inf:
            distance = msg.range_max
        elif distance == -math.inf:
            distance = 0.0
        elif not distance >= msg.range_min:   # nan compares False, so it lands here too
            continue
        angle = math.remainder(msg.angle_min + index * msg.angle_increment, 2 * math.pi)
        result.append((angle, distance))
    return result


def free_distance(msg, readings, heading, half_width=WINDOW):
    # How far the robot can go toward heading. A direction where most beams are missing (a short
    # scan, invalid readings) counts as blocked: what the laser does not see could be a wall.
    seen = [d for a, d in readings if abs(math.remainder(a - heading, 2 * math.pi)) <= half_width]
    expected = 2 * half_width / abs(msg.angle_increment) if msg.angle_increment else math.inf
    if len(seen) < expected * 2 / 3:
        return 0.0
    return min(seen)


def callback(msg):
    global turn
    readings = beams(msg)
    free = {heading: free_distance(msg, readings, heading) for heading in HEADINGS}
    best = max(HEADINGS, key=lambda h: min(free[h], FAR_ENOUGH) - 0.3 * abs(h))
    ahead = free[0.0]
    left = free_distance(msg, readings, math.radians(70), math.radians(40))
    right = free_distance(msg, readings, math.radians(-70), math.radians(40))
    if not readings:
        move.linear.x = 0.0                   # sees nothing at all: stand still
        move.angular.z = 0.0
    elif ahead < STOP_DISTANCE:
        move.linear.x = 0.0                   # blocked ahead: turn on the spot toward open space,
        if not turn:                          # and keep that way until the way ahead is free:
            turn = TURN_SPEED if best > 0 or (best == 0 and left > right) else -TURN_SPEED
        move.angular.z = turn                 # choosing at each scan, it can swing back and forth
    else:
        turn = 0.0
        move.linear.x = SPEED * min(1.0, ahead / SLOW_DISTANCE)
        move.angular.z = max(-TURN_SPEED, min(TURN_SPEED, 1.5 * best))
        if min(left, right) < SIDE_DISTANCE:  # something close beside: steer away from it
            move.angular.z = -TURN_SPEED / 2 if left < right else TURN_SPEED / 2
    pub.publish(move)


def stop():
    # The robot keeps its last command: leave it standing, not driving into the next wall.
    pub.publish(Twist())


rospy.init_node('wander')
pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
move = Twist()
rospy.on_shutdown(stop)
sub = rospy.Subscriber('/scan', LaserScan, callback)  # last: the callback uses all of the above
rospy.spin()
