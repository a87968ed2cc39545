"""The behaviour of TurtleBot3's drive node (turtlebot3_drive), as a pure state machine.

It looks at three beams: front (beam 0), left (beam 30) and right (beam 330). With the front
closer than 0.7 m it turns right by 30 degrees; else with the left closer than 0.6 m it turns
right, with the right closer than 0.6 m it turns left; else it drives forward at 0.3 m/s. Turns
are on the spot at 1.5 rad/s. Unlike the original it waits for a first scan before moving, reads
the beams by angle (any scan length works), and measures the turn with a wrapped yaw difference.
"""
import math

from fake_tb3.kinematics import wrap_angle
from fake_tb3.lidar import LDS_01

FRONT_LIMIT = 0.7
SIDE_LIMIT = 0.6
ESCAPE_TURN = math.radians(30)
LINEAR_SPEED = 0.3
ANGULAR_SPEED = 1.5
# The directions of beams 0, 30 and 330 of the LDS-01 scan.
FRONT_ANGLE = 0.0
LEFT_ANGLE = 30 * LDS_01.angle_increment
RIGHT_ANGLE = 330 * LDS_01.angle_increment


def beam(ranges, angle_min, angle_increment, range_max, angle):
    """The range of the beam nearest to `angle` (rad, 0..2pi), inf read as range_max and NaN (a
    failed measurement) as 0 so that it counts as an obstacle. None if no beam points within half
    an increment of `angle`."""
    if not ranges or not angle_increment > 0:
        return None
    turns = (angle - angle_min) / (2 * math.pi)
    for offset in (math.floor(turns), math.ceil(turns)):  # the scan may start anywhere
        index = round((angle - angle_min - offset * 2 * math.pi) / angle_increment)
        if 0 <= index < len(ranges):
            value = ranges[index]
            if math.isnan(value):
                return 0.0
            return range_max if math.isinf(value) else value
    return None


def read_beams(scan_ranges, angle_min, angle_increment, range_max):
    """(front, left, right) distances of a scan, or None when it lacks one of the three beams."""
    distances = tuple(beam(scan_ranges, angle_min, angle_increment, range_max, angle)
                      for angle in (FRONT_ANGLE, LEFT_ANGLE, RIGHT_ANGLE))
    return None if None in distances else distances


class Turtlebot3Drive:
    """The wanderer of turtlebot3_simulation: decides the next (linear, angular) command from the
    latest beams and the current yaw."""

    def __init__(self):
        self.turn_direction = 0  # +1 left, -1 right, 0 not turning
        self.turn_start_yaw = 0.0

    def command(self, beams, yaw):
        """beams: (front, left, right) or None before the first usable scan."""
        if self.turn_direction:
            if abs(wrap_angle(yaw - self.turn_start_yaw)) < ESCAPE_TURN:
                return 0.0, self.turn_direction * ANGULAR_SPEED
            self.turn_direction = 0
        if beams is None:
            return 0.0, 0.0
        front, left, right = beams
        if front < FRONT_LIMIT or left < SIDE_LIMIT:
            self.turn_direction = -1
        elif right < SIDE_LIMIT:
            self.turn_direction = 1
        else:
            return LINEAR_SPEED, 0.0
        self.turn_start_yaw = yaw
        return 0.0, self.turn_direction * ANGULAR_SPEED
