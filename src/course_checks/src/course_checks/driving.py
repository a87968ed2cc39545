"""What the simulated TurtleBot3 did, judged from fake_tb3's (sim time s, x, y, yaw) poses, scans
and commands: the circle and the command rate of trajectory.py, the stop of avoid_obstacle.py."""
import math

from course_checks import figures
from course_checks.rates import kept_rate
from course_checks.robot import largest_move, travelled
from course_checks.verdict import Verdict, decimal

# Measurement constants of fake_tb3, not grading choices (those are the caller's, from the rubric):
STILL_M = 1e-4        # fake_tb3's odometry has no noise: a robot standing still moves by rounding only
STILL_SLACK_S = 0.1   # a window of poses may begin this much after its start (odometry at 30 Hz, late when busy)
SCAN_HZ = 5           # fake_tb3's scans a simulated second (the LDS-01's rate)
WATCH_SLACK_S = 0.5   # a watch the run's deadline ended this much (simulated) short still counts


def commands_kept(commands, seconds, linear, angular, speed_tolerance, rate_hz, rate_tolerance):
    """(sim time, linear.x, angular.z) commands, heard over `seconds` of simulated time, are all
    linear, angular (within speed_tolerance) at rate_hz (within rate_tolerance, kept_rate)."""
    rate = kept_rate([t for t, _, _ in commands]) if len(commands) >= 2 else 0.0
    wrong = [(lin, ang) for _, lin, ang in commands
             if abs(lin - linear) > speed_tolerance or abs(ang - angular) > speed_tolerance]
    seen = '%d messages in %.1f simulated seconds, %.2f Hz' % (len(commands), seconds, rate)
    if wrong:
        seen += ', among them linear.x %g, angular.z %g' % wrong[0]
    return Verdict(abs(rate - rate_hz) <= rate_tolerance and not wrong and len(commands) >= 2, seen)


def circle_through(poses, radius, spawn, tolerance, min_travel):
    """The poses lie on a circle of `radius` through the spawn (x, y): the fitted radius, every
    pose's distance to the fitted circle and the spawn's, within tolerance * radius; a robot that
    drove less than min_travel metres drove no circle."""
    length = travelled(poses)
    if length < min_travel:
        return Verdict(False, 'the robot moved %.2f m in %.0f simulated seconds' % (length, poses[-1][0] - poses[0][0]))
    cx, cy, fitted = figures.fit_circle([(x, y) for _, x, y, _ in poses])
    off = max(abs(math.hypot(x - cx, y - cy) - radius) for _, x, y, _ in poses)
    through_spawn = abs(math.hypot(cx - spawn[0], cy - spawn[1]) - radius)
    limit = tolerance * radius
    ok = abs(fitted - radius) <= limit and off <= limit and through_spawn <= limit
    return Verdict(ok, 'a circle of radius %.3f m centred at (%s, %s), positions up to %.3f m off it' % (
        fitted, decimal(cx, 2), decimal(cy, 2), off))


def stopped_for(poses, seconds):
    """The robot has stood still over the last `seconds` of simulated time of these poses."""
    recent = [p for p in poses if p[0] >= poses[-1][0] - seconds]
    return recent[0][0] <= poses[-1][0] - seconds + STILL_SLACK_S and largest_move(recent) < STILL_M


def still_since(poses):
    """The first of the latest poses the robot has stood still at: where it stopped."""
    last = len(poses) - 1
    first = last
    while first > 0 and largest_move([poses[last], poses[first - 1]]) < STILL_M:
        first -= 1
    return poses[first]


def drove_off(poses, since, place):
    """The simulated time of the first of the poses after `since` s at which the robot had moved
    from `place` (x, y), where it stood then, by more than rounding; None while it has not."""
    for t, x, y, _ in poses:
        if t > since and math.hypot(x - place[0], y - place[1]) >= STILL_M:
            return t
    return None


def front_median(scans, seconds):
    """The front beam's median over the scans of the last `seconds` (three at least): one noisy
    reading does not decide."""
    fronts = sorted(scan.ranges[0] for scan in scans[-max(3, int(seconds * SCAN_HZ)):])
    return fronts[len(fronts) // 2]


def front_at_stop(scans, stay_seconds, low, high):
    """The front beam (the median over the scans of the stay_seconds watched after the stop) is
    between low and high metres."""
    front = front_median(scans, stay_seconds)
    return Verdict(low <= front <= high, 'stopped with the front beam at %.3f m (median over the stop)' % front)


def stayed(after, collisions, max_creep, stay_seconds):
    """From the stop (the first of the poses `after`) on, for stay_seconds of simulated time, the
    robot touched nothing and moved at most max_creep metres."""
    creep = largest_move(after)
    watched = after[-1][0] - after[0][0]
    ok = collisions == 0 and creep <= max_creep and watched >= stay_seconds - WATCH_SLACK_S
    return Verdict(ok, '%d collisions, %.3f m moved in %.1f s' % (collisions, creep, watched))
