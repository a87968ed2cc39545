"""Robots driving in a world: exact motion, collisions that stop at the contact, laser scans."""
import math

import numpy as np

from fake_tb3.geometry import box_outline, boxes_overlap, clearance, nearby
from fake_tb3.kinematics import arc_poses, wheel_turns, wrap_angle

# Longest step any point of the body may make between two overlap tests. Much smaller than the
# body, so a moving body cannot jump over an obstacle, however thin.
SUBSTEP_LENGTH = 0.005
# Substeps tested at once (bounds the memory of one test, whatever the speed).
SUBSTEPS_PER_BATCH = 256
# Bisection rounds that place the body at the contact (step / 2**12 away from it).
CONTACT_ROUNDS = 12
TRAIL_SPACING = 0.02


class SimRobot:
    """The state of one simulated TurtleBot3, in the world frame."""

    def __init__(self, name, model, x=0.0, y=0.0, yaw=0.0, laser=None):
        self.name = name
        self.model = model
        self.x, self.y, self.yaw = float(x), float(y), wrap_angle(float(yaw))
        self.laser = laser
        self.box = (model.body_offset_x, model.body_length / 2, model.body_width / 2)
        self.command = (0.0, 0.0)   # linear m/s, angular rad/s, held until the next command
        self.velocity = (0.0, 0.0)  # what the robot really did over the last step
        self.wheel_angles = (0.0, 0.0)  # left, right, rad
        self.in_contact = False
        self.collisions = 0  # contacts begun since the start
        # How far any point of the body may still move before it could touch something: while
        # this lasts, motion needs no overlap test. 0: unknown, test.
        self.free_travel = 0.0
        self.trail = [(self.x, self.y)]
        self.last_scan = None  # (x, y, yaw of the laser, ranges) of the latest scan
        self._outline_pose = self._outline = None

    @property
    def pose(self):
        return self.x, self.y, self.yaw

    def outline(self):
        """The sides of the body, as others see and hit it (kept until the robot moves)."""
        if self._outline_pose != self.pose:
            self._outline_pose, self._outline = self.pose, box_outline(*self.pose, self.box)
        return self._outline

    def laser_pose(self):
        sx, sy, _ = self.model.scan_offset
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return self.x + c * sx - s * sy, self.y + s * sx + c * sy, self.yaw


def sweep(robot, dt):
    """The longest path any point of the body travels in dt seconds with its command."""
    linear, angular = robot.command
    return (abs(linear) + abs(angular) * robot.model.body_corner_radius) * dt


def _first_overlap(robot, dt, segments, circles):
    """Fraction of the step (0..1] at which the body first overlaps an obstacle, None if never.

    Returns (blocked_fraction, free_fraction): the substep that overlaps and the one before it.
    """
    model = robot.model
    linear, angular = robot.command
    travel = sweep(robot, dt)
    substeps = max(1, math.ceil(travel / SUBSTEP_LENGTH))
    for first in range(0, substeps, SUBSTEPS_PER_BATCH):
        count = min(SUBSTEPS_PER_BATCH, substeps - first)
        fractions = np.arange(first + 1, first + count + 1) / substeps
        # Only the obstacles this batch can reach: around the middle of its path.
        mid_x, mid_y, _ = arc_poses(robot.x, robot.y, robot.yaw, linear, angular,
                                    dt * (first + count / 2) / substeps)
        reach = travel * count / substeps / 2 + model.body_corner_radius
        near_segments, near_circles = nearby(segments, circles, float(mid_x), float(mid_y), reach)
        if not len(near_segments) and not len(near_circles):
            continue
        poses = arc_poses(robot.x, robot.y, robot.yaw, linear, angular, fractions * dt)
        overlap = boxes_overlap(poses, robot.box, near_segments, near_circles)
        if overlap.any():
            index = int(np.argmax(overlap))
            return fractions[index], (fractions[index - 1] if index else first / substeps)
    return None


def _contact_fraction(robot, linear, angular, dt, blocked, free, segments, circles):
    """Largest fraction in [free, blocked) where the body is still clear, by bisection."""
    for _ in range(CONTACT_ROUNDS):
        middle = (free + blocked) / 2
        pose = arc_poses(robot.x, robot.y, robot.yaw, linear, angular, middle * dt)
        if boxes_overlap(pose, robot.box, segments, circles)[0]:
            blocked = middle
        else:
            free = middle
    return free


def drive(robot, dt, segments, circles):
    """Move `robot` for dt seconds with its command, stopping at the first contact.

    Returns True when this step began a new contact (the robot was free before).
    """
    linear, angular = robot.command
    if dt <= 0:
        return False
    fraction = 1.0
    travel = sweep(robot, dt)
    if travel > robot.free_travel:
        overlap = _first_overlap(robot, dt, segments, circles)
        if overlap is not None:
            fraction = _contact_fraction(robot, linear, angular, dt, *overlap, segments, circles)
        robot.free_travel = 0.0
    robot.free_travel -= travel * fraction
    duration = fraction * dt
    x, y, yaw = arc_poses(robot.x, robot.y, robot.yaw, linear, angular, duration)
    robot.x, robot.y, robot.yaw = float(x), float(y), wrap_angle(float(yaw))
    left, right = wheel_turns(linear * duration, angular * duration, robot.model)
    robot.wheel_angles = (robot.wheel_angles[0] + left, robot.wheel_angles[1] + right)
    robot.velocity = (linear * fraction, angular * fraction)
    last_x, last_y = robot.trail[-1]
    if math.hypot(robot.x - last_x, robot.y - last_y) >= TRAIL_SPACING:
        robot.trail.append((robot.x, robot.y))
    began_contact = fraction < 1.0 and not robot.in_contact
    if fraction < 1.0:
        robot.in_contact = True
        robot.collisions += began_contact
    elif linear or angular:
        robot.in_contact = False
    if robot.free_travel <= 0.0 and travel > 0.0:
        robot.free_travel = (clearance(robot.x, robot.y, segments, circles)
                             - robot.model.body_corner_radius)
    return began_contact


class Simulation:
    """A world and the robots in it. Robots see and hit each other's bodies when
    `robots_see_each_other` (they never overlap then)."""

    def __init__(self, world, robots, robots_see_each_other=True):
        self.world = world
        self.robots = list(robots)
        self.robots_see_each_other = robots_see_each_other

    def obstacles_for(self, robot):
        """(segments, circles) that `robot` sees and hits."""
        segments = self.world.segments
        if self.robots_see_each_other and len(self.robots) > 1:
            segments = np.vstack([segments] + [other.outline() for other in self.robots
                                               if other is not robot])
        return segments, self.world.circles

    def overlapping(self, robot):
        """Whether robot's body overlaps an obstacle now (a spawn pose inside something)."""
        return bool(boxes_overlap(robot.pose, robot.box, *self.obstacles_for(robot))[0])

    def step(self, dt):
        """Advance every robot by dt seconds; returns the robots that began a contact."""
        if self.robots_see_each_other and len(self.robots) > 1:
            # What the others may travel comes out of each robot's free travel too.
            travels = [sweep(robot, dt) for robot in self.robots]
            for robot, travel in zip(self.robots, travels):
                robot.free_travel -= sum(travels) - travel
        return [robot for robot in self.robots if drive(robot, dt, *self.obstacles_for(robot))]

    def scan(self, robot):
        """A laser scan of `robot` now (ranges array), also kept as robot.last_scan."""
        laser_x, laser_y, laser_yaw = robot.laser_pose()
        ranges = robot.laser.scan(laser_x, laser_y, laser_yaw, *self.obstacles_for(robot))
        robot.last_scan = (laser_x, laser_y, laser_yaw, ranges)
        return ranges
