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
    chord = _chord(linear, t, turn)
    heading = yaw + turn / 2
    return x + chord * np.cos(heading), y + chord * np.sin(heading), yaw + turn


def _chord(linear, t, turn):
    return linear * t * np.sinc(turn / (2 * math.pi))  # np.sinc(u) = sin(pi u) / (pi u)


class HeldStep:
    """arc_poses, wrap_angle and wheel_turns of steps of one `duration` with a held command, for
    Python floats, at a fraction of the cost of numpy on scalars: what does not depend on the pose
    is made once, and the headings of the next steps are planned ahead (the yaw does not depend on
    x and y) so that numpy takes the cos and sin of many in one call. The operations on each pose
    are those of arc_poses in the same order, and numpy's cos and sin give each element what they
    give it alone: the poses are the same to the last bit."""

    AHEAD = 64  # steps planned at once

    def __init__(self, command, duration, model):
        """command: (linear m/s, angular rad/s)."""
        self.command, self.duration = command, duration
        linear, angular = command
        turn = angular * duration
        self.turn, self.half_turn = turn, turn / 2
        self.chord = float(_chord(linear, np.float64(duration), np.float64(turn)))
        self.left, self.right = wheel_turns(linear * duration, turn, model)
        self._yaws = self._cos = self._sin = ()  # of the planned steps (_plan)
        self._next = 0  # the next planned step

    def _plan(self, yaw, count):
        yaws = [yaw]
        for _ in range(count):
            yaws.append(wrap_angle(yaws[-1] + self.turn))
        headings = np.array(yaws[:-1]) + self.half_turn
        self._yaws = yaws
        self._cos, self._sin = np.cos(headings).tolist(), np.sin(headings).tolist()
        self._next = 0

    def pose_after(self, x, y, yaw):
        """(x, y, yaw) reached from (x, y, yaw); yaw wrapped."""
        if self._next >= len(self._cos):
            # Twice as many as the last plan, which ran to its end (one at first: a contact's
            # step is made once, as its duration is its own).
            self._plan(yaw, min(2 * len(self._cos), self.AHEAD) or 1)
        elif self._yaws[self._next] != yaw:  # moved by something else (several robots at once)
            self._plan(yaw, 1)
        index = self._next
        self._next = index + 1
        return (x + self.chord * self._cos[index], y + self.chord * self._sin[index],
                self._yaws[index + 1])


def wheel_turns(distance, rotation, model):
    """Angles (rad) the left and right wheels turn while the robot drives `distance` along its path
    and turns by `rotation`."""
    half_track = rotation * model.wheel_separation / 2
    return ((distance - half_track) / model.wheel_radius,
            (distance + half_track) / model.wheel_radius)
