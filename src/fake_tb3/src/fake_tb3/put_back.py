"""The grader's second start of a run: once a robot has driven and then stood still for a while, it
is put back along its heading, as a hand would. A node that answers its scans drives and stops
again; one that drives by the clock and reads nothing stays where it is put.

The grader draws the moment and the distance at each grading and hands them to fake_tb3 outside
the ROS graph (course_grader starts fake_tb3 through a FIFO only the grader can write): nothing a
node can read tells them before the robot moves. Distances in metres, times in simulated seconds.
"""
import json
import math

# m and rad: a robot whose command is zero does not move at all; anything above this is a move.
STILL = 1e-9


class SettingsError(ValueError):
    """Settings the grader gave that fake_tb3 cannot use; the text says why."""


def from_settings(text):
    """The put-back's {'min_drive', 'after', 'distance'} from the grader's settings (JSON, an object
    whose optional key put_back holds them), None for no settings or none of it."""
    if not text.strip():
        return None
    try:
        settings = json.loads(text)
    except ValueError as error:
        raise SettingsError('the grader\'s settings are not JSON: %s' % error) from None
    if not isinstance(settings, dict):
        raise SettingsError('the grader\'s settings must be a JSON object, got %r' % (settings,))
    put_back = settings.get('put_back')
    if put_back is None:
        return None
    if not isinstance(put_back, dict) or sorted(put_back) != ['after', 'distance', 'min_drive']:
        raise SettingsError('put_back must be an object of min_drive, after and distance, got %r'
                            % (put_back,))
    for key, value in sorted(put_back.items()):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                math.isfinite(value) and value > 0):
            raise SettingsError('put_back %s must be a positive number, got %r' % (key, value))
    return put_back


class PutBack:
    """One robot's put-back: after it got `min_drive` m from its spawn pose and then stood still
    for `after` s in a row, it is moved `distance` m back along its heading, once (or to its spawn
    pose where that place is taken)."""

    def __init__(self, robot, min_drive, after, distance):
        self.robot = robot
        self.min_drive, self.after, self.distance = float(min_drive), float(after), float(distance)
        self.spawn = robot.pose
        self.driven = False
        self.last_pose, self.last_time = robot.pose, 0.0
        self.still_since = None   # simulated time from which the robot has not moved
        self.done = False

    def after_step(self, simulation):
        """To call after each of the simulation's steps. None, or once, when it put the robot
        back: {'still_since', 'from', 'to'} (poses x, y, yaw), at simulation.time."""
        if self.done:
            return None
        robot, now = self.robot, simulation.time
        pose = robot.pose
        moved = any(abs(a - b) > STILL for a, b in zip(pose, self.last_pose))
        if math.hypot(pose[0] - self.spawn[0], pose[1] - self.spawn[1]) >= self.min_drive:
            self.driven = True
        if moved or not self.driven:
            self.still_since = None
        elif self.still_since is None:
            self.still_since = self.last_time   # unmoved since the pose of the step before
        self.last_pose, self.last_time = pose, now
        if self.still_since is None or now - self.still_since < self.after - 1e-9:
            return None
        self.done = True
        x, y, yaw = pose
        back = (x - self.distance * math.cos(yaw), y - self.distance * math.sin(yaw), yaw)
        if not simulation.place(robot, *back):
            back = self.spawn
            simulation.place(robot, *back)
        self.last_pose = robot.pose
        return {'still_since': self.still_since, 'from': pose, 'to': robot.pose}
