"""Robots driving in a world: exact motion, collisions that stop at the contact, laser scans."""
import copy
import logging
import math
import types

import numpy as np

from fake_tb3.geometry import box_outlines, boxes_overlap, clearance, nearby
from fake_tb3.kinematics import HeldStep, arc_poses, wheel_turns, wrap_angle
from fake_tb3.lidar import scan_all

# Longest step any point of the body may make between two overlap tests. Much smaller than the
# body, so a moving body cannot jump over an obstacle, however thin.
SUBSTEP_LENGTH = 0.005
# Substeps tested at once (bounds the memory of one test, whatever the speed). The first batch
# near an obstacle is small, as a robot pushing on a contact overlaps at its first substep.
SUBSTEPS_PER_BATCH = 256
FIRST_BATCH = 16
# Where the disc around the body comes this close (m) to an obstacle, poses are tested one by one;
# farther away the path is skipped.
TEST_ZONE = 0.25
# A robot in contact that moves more than this (m) before meeting an obstacle again has left the
# first contact: the new one counts.
CONTACT_TOLERANCE = 1e-4
# Rounds that place the body at the contact, each testing CONTACT_SAMPLES poses spread between
# the last clear pose and the first blocked one: it ends a substep / 64**2 away from the contact.
CONTACT_ROUNDS = 2
CONTACT_SAMPLES = 63
TRAIL_SPACING = 0.02
# Robots free to move that step together, in one go (fewer move one by one, which costs less).
TOGETHER = 4
# m/s. No point of the body may move faster: a command that asks more is scaled down, so that
# the pose stays a finite number (at 1e308 m/s it would overflow within two seconds).
SPEED_OF_LIGHT = 299792458.0


class SimRobot:
    """The state of one simulated TurtleBot3, in the world frame."""

    def __init__(self, name, model, x=0.0, y=0.0, yaw=0.0, laser=None):
        self.name = name
        self.model = model
        self.x, self.y, self.yaw = float(x), float(y), wrap_angle(float(yaw))
        self.laser = laser
        self.box = (model.body_offset_x, model.body_length / 2, model.body_width / 2)
        self.command = (0.0, 0.0)   # linear m/s, angular rad/s, held until the next command
        self.command_time = 0.0     # simulated time of the latest command
        self.timed_out = False      # stopped by the command timeout since the latest command
        self.velocity = (0.0, 0.0)  # what the robot really did over the last step
        self.wheel_angles = (0.0, 0.0)  # left, right, rad
        self.in_contact = False
        self.collisions = 0  # contacts begun since the start
        # How far any point of the body may still move before it could touch something: while
        # this lasts, motion needs no overlap test. 0: unknown, test.
        self.free_travel = 0.0
        self.trail = [(self.x, self.y)]
        self.last_scan = None  # (x, y, yaw of the laser, ranges) of the latest scan
        self.held_step = None  # the HeldStep of the latest full step, for the next ones

    @property
    def label(self):
        """The name in log lines."""
        return self.name or 'robot'

    @property
    def pose(self):
        return self.x, self.y, self.yaw

    def laser_pose(self):
        sx, sy, _ = self.model.scan_offset
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return self.x + c * sx - s * sy, self.y + s * sx + c * sy, self.yaw


def sweep(robot, dt):
    """The longest path any point of the body travels in dt seconds with its command."""
    linear, angular = robot.command
    return (abs(linear) + abs(angular) * robot.model.body_corner_radius) * dt


def _first_overlap(robot, dt, segments, circles):
    """(blocked, free, near_segments, near_circles): the fractions of the step of the first tested
    pose that overlaps an obstacle and of the one before it, and the obstacles near them; None if
    the path is clear.

    The cost is bounded whatever the speed. A command held over a step turns the body about a
    fixed centre, so after one full turn it is back where it started: at most one turn is tested.
    The body stays within body_corner_radius of its base point; where that disc is farther than
    TEST_ZONE from every obstacle, the path is skipped for as far as the base point can go without
    the disc touching anything (conservative advancement: steps grow as the path leaves the
    obstacles behind). Only near obstacles are poses tested, SUBSTEP_LENGTH apart for the fastest
    point of the body, in batches.
    """
    linear, angular = robot.command
    radius = robot.model.body_corner_radius
    base_travel = abs(linear) * dt  # path of the base point over the whole step
    end = 1.0
    if angular * dt:
        end = min(1.0, 2 * math.pi / abs(angular * dt))
    travel = sweep(robot, dt)
    if not travel:
        return None
    substep = SUBSTEP_LENGTH / travel
    start, batch = 0.0, FIRST_BATCH
    while start < end:
        x, y, _ = arc_poses(robot.x, robot.y, robot.yaw, linear, angular, start * dt)
        x, y = float(x), float(y)
        free = clearance(x, y, segments, circles) - radius
        if free > TEST_ZONE:
            if not base_travel:  # the base point stays: the disc stays clear
                return None
            start += free / base_travel
            continue
        count = max(1, min(batch, math.ceil((end - start) / substep)))
        batch = min(4 * batch, SUBSTEPS_PER_BATCH)
        fractions = np.minimum(start + substep * np.arange(1, count + 1), end)
        # Only the obstacles this batch can reach: its base point moves at most count substeps.
        near_segments, near_circles = nearby(segments, circles, x, y,
                                             count * SUBSTEP_LENGTH + radius)
        if len(near_segments) or len(near_circles):
            poses = arc_poses(robot.x, robot.y, robot.yaw, linear, angular, fractions * dt)
            overlap = boxes_overlap(poses, robot.box, near_segments, near_circles)
            if overlap.any():
                index = int(np.argmax(overlap))
                return (fractions[index], (fractions[index - 1] if index else start),
                        near_segments, near_circles)
        start = float(fractions[-1])
    return None


def _contact_fraction(robot, dt, blocked, free, segments, circles):
    """Largest fraction in [free, blocked) where the body is still clear, to a 64**2th."""
    linear, angular = robot.command
    for _ in range(CONTACT_ROUNDS):
        fractions = np.linspace(free, blocked, CONTACT_SAMPLES + 2)[1:-1]
        poses = arc_poses(robot.x, robot.y, robot.yaw, linear, angular, fractions * dt)
        overlap = boxes_overlap(poses, robot.box, segments, circles)
        if overlap.any():
            index = int(np.argmax(overlap))
            blocked, free = fractions[index], (fractions[index - 1] if index else free)
        else:
            free = fractions[-1]
    return free


def step_robot(robot, dt, travel, obstacles):
    """Move `robot` for dt seconds with its command (whose sweep is `travel`), stopping at the
    first contact. obstacles() returns the (segments, circles) it may hit: asked for only when
    its free travel is used up.

    Returns True when this step began a new contact: the robot was free before, or it left the
    contact it was in (moved more than CONTACT_TOLERANCE) and met an obstacle again.
    """
    if dt <= 0:
        return False
    fraction = 1.0
    if travel > robot.free_travel:
        if travel:
            segments, circles = obstacles()
            overlap = _first_overlap(robot, dt, segments, circles)
            if overlap is not None:
                fraction = _contact_fraction(robot, dt, *overlap)
        robot.free_travel = 0.0
    held = robot.held_step
    duration = fraction * dt
    if held is None or held.command is not robot.command or held.duration != duration:
        held = HeldStep(robot.command, duration, robot.model)
        if fraction == 1.0:  # a contact's step is not the next one's
            robot.held_step = held
    robot.x, robot.y, robot.yaw = held.pose_after(robot.x, robot.y, robot.yaw)
    robot.wheel_angles = (robot.wheel_angles[0] + held.left, robot.wheel_angles[1] + held.right)
    return _moved(robot, travel, fraction, obstacles)


def step_free_robots(robots, travels, dt, obstacles_for):
    """step_robot for robots whose step needs no overlap test (their free travel covers their
    sweep, `travels`, or they stay), all of them in one go. obstacles_for(robot) is step_robot's
    obstacles() of each."""
    linear = np.array([robot.command[0] for robot in robots])
    angular = np.array([robot.command[1] for robot in robots])
    x, y, yaw = arc_poses(np.array([robot.x for robot in robots]),
                          np.array([robot.y for robot in robots]),
                          np.array([robot.yaw for robot in robots]), linear, angular, dt)
    wheels = types.SimpleNamespace(
        wheel_separation=np.array([robot.model.wheel_separation for robot in robots]),
        wheel_radius=np.array([robot.model.wheel_radius for robot in robots]))
    left, right = wheel_turns(linear * dt, angular * dt, wheels)
    for robot, travel, x, y, yaw, left, right in zip(robots, travels, x.tolist(), y.tolist(),
                                                     wrap_angle(yaw).tolist(), left.tolist(),
                                                     right.tolist()):
        robot.x, robot.y, robot.yaw = x, y, yaw
        robot.wheel_angles = (robot.wheel_angles[0] + left, robot.wheel_angles[1] + right)
        if travel > robot.free_travel:  # it stays, and others came nearer
            robot.free_travel = 0.0
        _moved(robot, travel, 1.0, lambda robot=robot: obstacles_for(robot))


def _moved(robot, travel, fraction, obstacles):
    """What follows a step in which robot moved `fraction` of its command's path (of length
    `travel`): speed, trail, contacts, free travel. Returns True when it began a contact."""
    linear, angular = robot.command
    robot.free_travel -= travel * fraction
    robot.velocity = (linear * fraction, angular * fraction)
    last_x, last_y = robot.trail[-1]
    if math.hypot(robot.x - last_x, robot.y - last_y) >= TRAIL_SPACING:
        robot.trail.append((robot.x, robot.y))
    began_contact = fraction < 1.0 and (not robot.in_contact
                                        or travel * fraction > CONTACT_TOLERANCE)
    if fraction < 1.0:
        robot.in_contact = True
        robot.collisions += began_contact
    elif linear or angular:
        robot.in_contact = False
    if robot.free_travel <= 0.0 and travel > 0.0:
        robot.free_travel = (clearance(robot.x, robot.y, *obstacles())
                             - robot.model.body_corner_radius)
    return began_contact


class CommandError(ValueError):
    """A velocity command the simulator refuses; the text says why."""


class Simulation:
    """A world and the robots in it. Robots see and hit each other's bodies when
    `robots_see_each_other` (they never overlap then).

    The caller drives it: velocity commands through command() between steps, then step(dt).
    A robot that gets no command for `command_timeout` simulated seconds stops (0: never, as in
    Gazebo); with `clamp_speed` commands are limited to the model's maximum speeds. Log lines go
    to `log`, an object with info() and warning() (a logging.Logger will do).
    """

    def __init__(self, world, robots, robots_see_each_other=True, command_timeout=0.0,
                 clamp_speed=False, log=None):
        self.world = world
        self.robots = list(robots)
        self.robots_see_each_other = robots_see_each_other
        if not (command_timeout >= 0 and math.isfinite(command_timeout)):
            raise ValueError('command timeout must be a finite number >= 0, got %r'
                             % (command_timeout,))
        self.command_timeout = command_timeout
        self.clamp_speed = clamp_speed
        self.log = log or logging.getLogger('fake_tb3')
        self.time = 0.0  # simulated seconds since the start
        self._outlines_poses = self._outlines = None

    def command(self, robot, linear, angular):
        """Make (linear m/s, angular rad/s) `robot`'s command from now until the next one.

        Raises CommandError for a NaN or infinite velocity (the previous command holds). Returns
        None, or the text of a warning when the command was limited: to the model's maximum with
        clamp_speed, and always so that no point of the body outruns light (a faster command
        keeps its path; its speeds are scaled down together).
        """
        if not (math.isfinite(linear) and math.isfinite(angular)):
            raise CommandError('%s: ignoring cmd_vel with a non-finite velocity (linear.x %s, '
                               'angular.z %s)' % (robot.label, linear, angular))
        notice = None
        if self.clamp_speed:
            linear, angular = robot.model.clamp(linear, angular)
        # In units of light speed, so that adding them cannot overflow.
        fastest = (abs(linear) / SPEED_OF_LIGHT
                   + abs(angular) * (robot.model.body_corner_radius / SPEED_OF_LIGHT))
        if fastest > 1.0:
            notice = ('%s: cmd_vel linear.x %g m/s, angular.z %g rad/s would move the body '
                      'faster than light; limited to linear.x %g, angular.z %g (same path)'
                      % (robot.label, linear, angular, linear / fastest, angular / fastest))
            linear, angular = linear / fastest, angular / fastest
        robot.command = (float(linear), float(angular))
        robot.command_time = self.time
        robot.timed_out = False
        return notice

    def _stop_silent_robots(self):
        """Stop the robots that got no command for command_timeout seconds."""
        for robot in self.robots:
            if (not robot.timed_out
                    and self.time - robot.command_time > self.command_timeout):
                robot.timed_out = True
                if robot.command != (0.0, 0.0):
                    robot.command = (0.0, 0.0)
                    self.log.info('%s: no cmd_vel for %.2f s, stopping'
                                  % (robot.label, self.command_timeout))

    def outlines(self):
        """Every robot's body sides as the others see and hit them, (4 x robots, 4) segments in
        the order of self.robots; made once for the robots' poses, in one go."""
        poses = [robot.pose for robot in self.robots]
        if poses != self._outlines_poses:
            self._outlines_poses = poses
            boxes = [robot.box for robot in self.robots]
            self._outlines = box_outlines(poses, boxes).reshape(-1, 4)
        return self._outlines

    def obstacles_for(self, robot):
        """(segments, circles) that `robot` sees and hits."""
        segments = self.world.segments
        if self.robots_see_each_other and len(self.robots) > 1:
            index = 4 * self.robots.index(robot)
            outlines = self.outlines()
            segments = np.concatenate([segments, outlines[:index], outlines[index + 4:]])
        return segments, self.world.circles

    def _obstacles_once(self, robot):
        """obstacles_for(robot), made on the first call only (each robot's step needs them
        seldom: building them from every other robot's outline was most of a step's cost)."""
        made = []

        def obstacles():
            if not made:
                made.append(self.obstacles_for(robot))
            return made[0]
        return obstacles

    def overlapping(self, robot):
        """Whether robot's body overlaps an obstacle now (a spawn pose inside something)."""
        return bool(boxes_overlap(robot.pose, robot.box, *self.obstacles_for(robot))[0])

    def place(self, robot, x, y, yaw):
        """Put `robot` at (x m, y m, yaw rad) at once, as a hand would: its command holds. False,
        and the robot stays, where its body would overlap an obstacle there."""
        before = robot.pose
        robot.x, robot.y, robot.yaw = float(x), float(y), wrap_angle(float(yaw))
        if not all(map(math.isfinite, robot.pose)) or self.overlapping(robot):
            robot.x, robot.y, robot.yaw = before
            return False
        robot.free_travel = 0.0   # unknown here: the next step tests
        robot.in_contact = False
        robot.trail.append((robot.x, robot.y))
        return True

    def step(self, dt):
        """Advance every robot by dt seconds; returns the robots that began a contact (each one
        is also logged as a warning)."""
        if self.command_timeout > 0:
            self._stop_silent_robots()
        began = []
        if dt > 0:
            travels = [sweep(robot, dt) for robot in self.robots]
            if self.robots_see_each_other and len(self.robots) > 1:
                # What the others may travel comes out of each robot's free travel too.
                total = sum(travels)
                for robot, travel in zip(self.robots, travels):
                    robot.free_travel -= total - travel
            # The robots whose step needs no overlap test move first, together (when they are
            # enough to gain by it); then the others one by one, each tested against where
            # everyone else is by then.
            free = [False] * len(self.robots)
            if len(self.robots) >= TOGETHER:
                free = [travel <= robot.free_travel or not travel
                        for robot, travel in zip(self.robots, travels)]
                if sum(free) >= TOGETHER:
                    step_free_robots(*zip(*[(robot, travel) for robot, travel, is_free
                                            in zip(self.robots, travels, free) if is_free]),
                                     dt, self.obstacles_for)
                else:
                    free = [False] * len(self.robots)
            began = [robot for robot, travel, is_free in zip(self.robots, travels, free)
                     if not is_free
                     and step_robot(robot, dt, travel, self._obstacles_once(robot))]
        self.time += dt
        for robot in began:
            self.log.warning('%s: collision at x %.3f y %.3f yaw %.3f: the body touches an '
                             'obstacle (collision %d)'
                             % (robot.label, robot.x, robot.y, robot.yaw, robot.collisions))
        return began

    def snapshot(self):
        """A copy of what a picture shows (the world, the robots' poses, trails and latest scans)
        to draw while the simulation goes on."""
        robots = []
        for robot in self.robots:
            robot_copy = copy.copy(robot)
            robot_copy.trail = list(robot.trail)
            robots.append(robot_copy)
        return Simulation(self.world, robots, self.robots_see_each_other)

    def scan(self, robot):
        """A laser scan of `robot` now (ranges array), also kept as robot.last_scan."""
        return self.scans([robot])[0]

    def scans(self, robots=None):
        """A laser scan of each of `robots` (default: all) now, cast together: a list of ranges
        arrays, each also kept as its robot's last_scan."""
        robots = self.robots if robots is None else list(robots)
        poses = [robot.laser_pose() for robot in robots]
        segments, owners = self.world.segments, None
        if self.robots_see_each_other and len(self.robots) > 1:
            # Every body is an obstacle, except to its own laser.
            segments = np.concatenate([segments, self.outlines()])
            scanned = np.full(len(self.robots) + 1, -1)
            for index, robot in enumerate(robots):
                scanned[self.robots.index(robot)] = index
            owners = np.concatenate([np.full(len(self.world.segments), -1),
                                     np.repeat(scanned[:-1], 4)])
        scans = scan_all([robot.laser for robot in robots], poses, segments, self.world.circles,
                         owners)
        for robot, pose, ranges in zip(robots, poses, scans):
            robot.last_scan = pose + (ranges,)
        return scans
