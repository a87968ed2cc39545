"""turtlesim's turtles as the checks see them: their poses recorded, their speeds in turtlesim's own
time, the circle a turtle drives, the poses a node printed, and moves no velocity explains (a
teleport or a /reset, which the labs do not use)."""
import math

import numpy
from turtlesim.msg import Pose
from turtlesim.world import TICK_SECONDS

from course_checks import figures, printed_poses, callers
from course_checks.verdict import Verdict, decimal
from course_common.topic_recorder import TopicRecorder

POSE_RATE_HZ = 1.0 / TICK_SECONDS   # turtlesim publishes the pose at every tick
JITTER = 0.25       # seconds a pose may arrive late on a busy machine (jumps)
# When a measurement starts (not grading choices: those are the caller's, from the rubric):
MOVING_M = 0.01      # over the last ten poses heard: the turtle moves
STILL_M = 1e-3       # over STILL_SECONDS of poses: the turtle stands still
STILL_SECONDS = 0.3
# The labs move turtles by cmd_vel; save_canvas writes where ~canvas_png says, and the course's
# turtlesim of a grading runs on the trusted side.
UNUSED_SERVICES = ('teleport_absolute', 'teleport_relative', 'reset', 'save_canvas')


def turtle_poses(turtle):
    """A recorder of the turtle's poses."""
    return TopicRecorder('/%s/pose' % turtle, Pose)


def pose_array(recorder):
    """The poses recorded so far as rows of x, y, theta, linear_velocity, angular_velocity."""
    return numpy.array([(pose.x, pose.y, pose.theta, pose.linear_velocity, pose.angular_velocity)
                        for pose in recorder.messages()])


def travelled(samples):
    """Distance travelled along recorded (time, pose) entries, in metres."""
    return figures.path_length([(pose.x, pose.y) for _, pose in samples])


def per_tick(samples):
    """(distance, heading change) of one turtlesim tick, the median over consecutive poses: the
    turtle's speed in turtlesim's own time (a fixed TICK_SECONDS a tick), which a busy machine that delays
    the ticks does not change, and a pose lost on the way does not skew."""
    steps = sorted(math.hypot(b.x - a.x, b.y - a.y) for (_, a), (_, b) in zip(samples, samples[1:]))
    turns = sorted(math.remainder(b.theta - a.theta, 2 * math.pi) for (_, a), (_, b) in zip(samples, samples[1:]))
    return steps[len(steps) // 2], turns[len(turns) // 2]


def tick_speeds(samples):
    """(linear m/s, angular rad/s) of the turtle in turtlesim's time, from per_tick."""
    step, turn = per_tick(samples)
    return step / TICK_SECONDS, turn / TICK_SECONDS


def drives_at(samples, linear, angular, tolerance):
    """The recorded (time, pose) entries show the turtle at linear m/s turning angular rad/s, each
    within tolerance (relative), in turtlesim's own time (tick_speeds)."""
    if len(samples) < 2:
        return Verdict(False, '%d poses heard' % len(samples))
    speed, rate = tick_speeds(samples)
    ok = abs(speed - linear) <= tolerance * abs(linear) and abs(rate - angular) <= tolerance * abs(angular)
    return Verdict(ok, '%.2f m/s turning %.2f rad/s' % (speed, rate))


def moving(recorder):
    """The turtle moved over the last ten poses heard."""
    return travelled(recorder.entries()[-10:]) > MOVING_M


def standing(recorder):
    """The turtle stands still over the next STILL_SECONDS of poses (records them)."""
    return travelled(recorder.record(STILL_SECONDS)) < STILL_M


def printed_position(printed, pose, tolerance):
    """Among the printed (x, y) is the pose's position, within tolerance (metres) on each."""
    matched = any(abs(x - pose.x) <= tolerance and abs(y - pose.y) <= tolerance for x, y in printed)
    return Verdict(matched, 'last printed x: %.2f, y: %.2f' % printed[-1] if printed
                   else 'no line `x: ..., y: ...` printed')


def at_pose(pose, expected, tolerance):
    """The pose is the expected (x, y, theta), each within tolerance."""
    seen = (pose.x, pose.y, pose.theta)
    return Verdict(max(abs(a - b) for a, b in zip(seen, expected)) <= tolerance, 'at (%.2f, %.2f, %.2f)' % seen)


def duration(samples):
    return samples[-1][0] - samples[0][0]


def turned(samples):
    """Heading change along the recorded poses in radians (counter-clockwise positive, unwrapped)."""
    return sum(math.remainder(b.theta - a.theta, 2 * math.pi)
               for (_, a), (_, b) in zip(samples, samples[1:]))


def jumps(samples, real_time_factor=1.0):
    """Moves between two heard poses that no velocity explains: (from (x, y), to (x, y)) of each.
    turtlesim moves a turtle at most |linear_velocity| * TICK_SECONDS a tick; between two poses heard
    dt wall seconds apart it had about dt / TICK_SECONDS ticks (JITTER more, for a pose a busy machine
    delayed), real_time_factor times as many on a simulated clock that fast. Farther than that (or
    at all, standing still at both ends): a teleport or /reset."""
    found = []
    for (t_a, a), (t_b, b) in zip(samples, samples[1:]):
        moved = math.hypot(b.x - a.x, b.y - a.y)
        speed = max(abs(a.linear_velocity), abs(b.linear_velocity))
        if moved > speed * real_time_factor * (t_b - t_a + JITTER) + 1e-3:
            found.append(((a.x, a.y), (b.x, b.y)))
    return found


def no_jumps(recorder, turtle, real_time_factor=1.0):
    """A failing verdict naming the first jump of the turtle, or None when it only drove."""
    found = jumps(recorder.entries(), real_time_factor)
    if not found:
        return None
    (x0, y0), (x1, y1) = found[0]
    return Verdict(False, '%s jumped %d times without driving there, first from (%.2f, %.2f) to (%.2f, %.2f): '
                   'a teleport or /reset, which this lab does not use' % (turtle, len(found), x0, y0, x1, y1))


def no_unused_calls(calls):
    """A failing verdict naming who called a teleport or /reset of turtlesim, among the calls
    [(service, caller)] turtlesim noted, or None when nobody did."""
    calls = callers.unused(calls, UNUSED_SERVICES)
    return callers.called(['x'], calls)['x'] if calls else None


def full_turn(radius):
    """How many moving poses make a full turn of a circle of `radius` at 1 m/s (and some)."""
    return int(2 * math.pi / radius / TICK_SECONDS) + 10


def moving_points(poses):
    """(x, y) of the poses (pose_array rows) at which the turtle moved forward."""
    return poses[poses[:, 3] > 0, :2] if len(poses) else poses


def circle(points, centre, radius, tolerance):
    """Points (N x 2) on a circle of `radius` around `centre`, within `tolerance` (relative): the
    fitted radius, the fitted centre and every point."""
    if len(points) < 3:
        return Verdict(False, '%d moving poses, too few for a circle' % len(points))
    centre_x, centre_y, fitted = figures.fit_circle(points)
    off_centre = math.hypot(centre_x - centre[0], centre_y - centre[1])
    off_circle = numpy.abs(numpy.hypot(points[:, 0] - centre[0], points[:, 1] - centre[1]) - radius).max()
    limit = tolerance * radius
    ok = abs(fitted - radius) <= limit and off_centre < limit and off_circle < limit
    return Verdict(ok, 'a circle of radius %.3f m centred at (%s, %s), %.3f m from the expected centre, '
                   'poses up to %.3f m off the expected circle (allowed %.3f m)' % (
                       fitted, decimal(centre_x, 3), decimal(centre_y, 3), off_centre, off_circle, limit))


def printed_poses_published(printed, recorder):
    """The printed (x, y, theta) are poses the simulator published, in order, keeping up with the
    turtle (printed_poses says how); the reason summarizes what was printed."""
    judgement = printed_poses.judge(printed, pose_array(recorder))
    wrong = printed_poses.problem(judgement)
    return Verdict(not wrong, wrong or printed_poses.summary(judgement))
