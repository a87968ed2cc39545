"""Differential drive kinematics, exact for a command held constant over a step."""
import math

import numpy as np


def wrap_angle(angle):
    """The same angle in [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def arc_poses(x, y, yaw, linear, angular, durations):
    """Poses reached after each of `durations` (s, array) driving (linear, angular) from a pose.

    A constant twist moves the robot along a circular arc (a line when angular is 0). The chord of
    the arc has length linear*t*sinc(angular*t/2) and points along the mean heading, which is exact
    for every angular, 0 included, without a special case.
    Returns arrays (x, y, yaw) of the shape of `durations`; yaw is not wrapped.
    """
    t = np.asarray(durations, dtype=float)
    turn = angular * t
    chord = linear * t * np.sinc(turn / (2 * math.pi))  # np.sinc(u) = sin(pi u) / (pi u)
    heading = yaw + turn / 2
    return x + chord * np.cos(heading), y + chord * np.sin(heading), yaw + turn


def wheel_turns(distance, rotation, model):
    """Angles (rad) the left and right wheels turn while the robot drives `distance` along its path
    and turns by `rotation`."""
    half_track = rotation * model.wheel_separation / 2
    return ((distance - half_track) / model.wheel_radius,
            (distance + half_track) / model.wheel_radius)
