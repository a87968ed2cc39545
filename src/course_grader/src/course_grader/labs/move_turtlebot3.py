"""The TurtleBot3 lab (seed 001): trajectory.py, laser_data.py, avoid_obstacle.py on fake_tb3, with
the checks of move_turtlebot3's own tests (move_turtlebot3_testing, test_trajectory, test_laser_data)."""
import math

from course_grader import feedback
from course_grader.labs.common import StudentNode, move_turtlebot3_testing, run_each, simulator
from course_grader.results import Outcome
from course_grader.session import Deadline
from course_testing.waiting import wait_until

import test_laser_data    # noqa: E402  (found through common's test_helpers)
import test_trajectory    # noqa: E402


def static_checks(session):
    """The scripts are executable, with a #! line that starts Python 3."""
    criterion = session.rubric.criterion('executable')
    problems, missing = [], []
    for name in criterion.get('scripts', []):
        path = session.script(name)
        if path is None:
            missing.append(name)
        else:
            problems += feedback.script_problems(path, session.relative(path))
    if missing:
        problems.insert(0, 'missing: %s' % ', '.join(missing))
    if problems:
        return {'executable': Outcome(False, 'expected `rosrun %s SCRIPT` to be able to start each '
                                      'script; seen: %s' % (session.rubric.package, problems[0]), problems[1:])}
    return {'executable': Outcome(True, 'all executable, with a Python 3 #! line')}


def _wait(condition, deadline, what, node=None):
    """Wait for condition() until the run's deadline; False on time-out, or as soon as the
    student's node (if given) has ended: nothing more will come from it."""
    def done():
        return condition() or (node is not None and node.ended())
    try:
        wait_until(done, deadline.left(), what=what, poll=0.05)
    except AssertionError:
        return False
    return bool(condition())


class Run:
    """The simulator and one of the student's nodes on it, watched, stopped at the end."""

    def __init__(self, session, script, picture=None, **sim_args):
        self.session = session
        self.stopped = False
        self.deadline = Deadline(session.rubric.limits['run_seconds'])
        self.watch = move_turtlebot3_testing.RobotWatch()
        self.sim = simulator(session, 'sim_%s.txt' % script.split('.')[0], picture, **sim_args)
        self.running = _wait(lambda: self.watch.copy('poses') and self.watch.copy('scans')
                             and self.watch.collisions is not None, self.deadline, 'fake_tb3')
        if not self.running:
            raise RuntimeError('the simulator did not start (see %s)' % 'sim_%s.txt' % script)
        self.node = StudentNode(session, script)

    def not_running(self, expected):
        """An outcome for a node that did not do anything: expected, and why (hints)."""
        hints = self.node.explain()
        return Outcome(False, 'expected %s; seen: %s' % (expected, hints[0] if hints else 'nothing'), hints[1:])

    def stop(self):
        if self.stopped:
            return
        self.stopped = True
        self.node.stop()
        self.sim.stop_in(15)
        self.watch.close()


def check_trajectory(session):
    rate_c = session.rubric.criterion('trajectory_rate')
    circle_c = session.rubric.criterion('trajectory_circle')
    linear, angular = rate_c.get('linear', 1.0), rate_c.get('angular', 1.0)
    run = Run(session, rate_c.get('script', 'trajectory.py'), picture='trajectory.png', world='empty',
              x_pos=0.0, y_pos=0.0, noise_stddev=0.0, real_time_factor=rate_c.get('real_time_factor', 10))
    try:
        watch = run.watch
        expected_rate = '%s: Twist linear.x %g m/s, angular.z %g rad/s on cmd_vel at %g Hz' % (
            run.node.name, linear, angular, rate_c.get('rate_hz', 1.0))
        if not _wait(lambda: watch.copy('commands'), run.deadline, 'a command', run.node):
            run.stop()
            failure = run.not_running(expected_rate)
            return {'trajectory_rate': failure,
                    'trajectory_circle': Outcome(False, 'not checked: %s published nothing' % run.node.name)}
        start = watch.now()
        period = 2 * math.pi / abs(angular) if angular else 10.0
        watched = circle_c.get('periods', 1.5) * period + 2
        _wait(lambda: watch.now() >= start + watched, run.deadline, 'simulated time')
        seen_for = watch.now() - start
        poses = watch.poses_since(start)
        commands = [(t, lin, ang) for t, lin, ang in watch.copy('commands') if t is not None and t >= start]
        run.stop()
        hints = run.node.explain()
        outcomes = {}
        # Rate and values of the commands, in simulated time.
        tolerance = rate_c.get('speed_tolerance', 0.01)
        if len(commands) >= 2:
            rate = (len(commands) - 1) / (commands[-1][0] - commands[0][0] or 1e-9)
        else:
            rate = 0.0
        wrong = [(lin, ang) for _, lin, ang in commands
                 if abs(lin - linear) > tolerance or abs(ang - angular) > tolerance]
        rate_ok = abs(rate - rate_c.get('rate_hz', 1.0)) <= rate_c.get('rate_tolerance', 0.1)
        seen = '%d messages in %.1f simulated seconds, %.2f Hz' % (len(commands), seen_for, rate)
        if wrong:
            seen += ', among them linear.x %g, angular.z %g' % wrong[0]
        outcomes['trajectory_rate'] = Outcome(rate_ok and not wrong and len(commands) >= 2,
                                              'expected %s; seen %s' % (expected_rate, seen), hints)
        # The circle of those commands, from the spawn pose.
        expected_radius = abs(linear / angular) if angular else float('inf')
        expected_circle = 'a circle of radius %.2f m through the spawn pose (0, 0)' % expected_radius
        length = move_turtlebot3_testing.travelled(poses)
        if length < 0.1:
            outcomes['trajectory_circle'] = Outcome(False, 'expected %s; seen: the robot moved %.2f m in '
                                                    '%.0f simulated seconds' % (expected_circle, length, seen_for), hints)
        else:
            cx, cy, radius = test_trajectory.fitted_circle(poses)
            off = max(abs(math.hypot(x - cx, y - cy) - expected_radius) for _, x, y, _ in poses)
            through_spawn = abs(math.hypot(cx, cy) - expected_radius)
            limit = circle_c.get('radius_tolerance', 0.05) * expected_radius
            ok = abs(radius - expected_radius) <= limit and off <= limit and through_spawn <= limit
            outcomes['trajectory_circle'] = Outcome(
                ok, 'expected %s (within %.2f m); seen a circle of radius %.3f m centred at (%.2f, %.2f), '
                'positions up to %.3f m off it' % (expected_circle, limit, radius, cx, cy, off), hints)
        return outcomes
    finally:
        run.stop()


def _normalized(lines):
    """Output lines with the separator line of any length (the slide's is cut short) as '=' * 10."""
    stripped = [line.strip() for line in lines]
    return ['=' * 10 if len(s) >= 3 and set(s) == {'='} else s for s in stripped]


def _as_number(text):
    try:
        return float(text)
    except ValueError:
        return None


def _same(printed, sent):
    if printed is None:
        return False
    if math.isnan(sent) or math.isnan(printed):
        return math.isnan(sent) and math.isnan(printed)
    return printed == sent or abs(printed - sent) <= 1e-3


def check_laser_data(session):
    criterion = session.rubric.criterion('laser_data')
    beams = criterion.get('beams', [0, 90, 180, 270, 359])
    needed = criterion.get('blocks', 8)
    run = Run(session, criterion.get('script', 'laser_data.py'), world='turtlebot3_world', x_pos=-2.0,
              y_pos=-0.5, noise_stddev=criterion.get('noise_stddev', 0.01),
              noise_seed=criterion.get('noise_seed', 7), real_time_factor=criterion.get('real_time_factor', 2))
    try:
        expected = ('%s prints, for every scan, ========== and the labels s1 [0] ... s5 [359] each '
                    'followed by the range of that beam (%s)' % (run.node.name, ', '.join(map(str, beams))))
        _wait(lambda: len(test_laser_data.printed_blocks(_normalized(run.node.lines))) >= needed,
              run.deadline, 'printed scans', run.node)
        blocks = test_laser_data.printed_blocks(_normalized(run.node.lines))
        scans = [[scan.ranges[i] if i < len(scan.ranges) else math.nan for i in beams]
                 for scan in run.watch.copy('scans')]
        run.stop()
        hints = run.node.explain()
        if not blocks:
            if not hints:
                hints = ['%d lines printed, none in the form of the slide (first: %r)' % (
                    len(run.node.lines), run.node.lines[0] if run.node.lines else '')]
            return {'laser_data': Outcome(False, 'expected %s; seen: %s' % (expected, hints[0]), hints[1:])}
        # Every block but the first and the newest: their scan certainly reached the grader too.
        checked = blocks[1:-1] or blocks
        unmatched = [block for block in checked
                     if not any(all(_same(_as_number(p), s) for p, s in zip(block, scan)) for scan in scans)]
        ok = len(blocks) >= needed and not unmatched
        seen = '%d scans printed, %d of %d checked match a published scan' % (
            len(blocks), len(checked) - len(unmatched), len(checked))
        if unmatched:
            seen += ' (one printed %s)' % ', '.join(unmatched[0])
        return {'laser_data': Outcome(ok, 'expected %s; seen %s' % (expected, seen), hints)}
    finally:
        run.stop()


def check_avoid_obstacle(session):
    stops_c = session.rubric.criterion('avoid_stops')
    stays_c = session.rubric.criterion('avoid_stays')
    run = Run(session, stops_c.get('script', 'avoid_obstacle.py'), picture='avoid_obstacle.png',
              world=stops_c.get('world', 'turtlebot3_world'), x_pos=stops_c.get('x_pos', -2.0),
              y_pos=stops_c.get('y_pos', -0.5), noise_stddev=stops_c.get('noise_stddev', 0.01),
              noise_seed=stops_c.get('noise_seed', 7), real_time_factor=stops_c.get('real_time_factor', 2))
    try:
        watch = run.watch
        low, high = stops_c.get('front_min', 0.35), stops_c.get('front_max', 0.5)
        expected = '%s drives at least %.1f m and stops with its front beam between %.2f and %.2f m' % (
            run.node.name, stops_c.get('min_drive', 0.5), low, high)
        spawn = watch.copy('poses')[0]

        def moved():
            return move_turtlebot3_testing.largest_move([spawn] + watch.copy('poses'))

        def stopped_for(seconds):
            poses = watch.copy('poses')
            recent = [p for p in poses if p[0] >= poses[-1][0] - seconds]
            return recent[0][0] <= poses[-1][0] - seconds + 0.1 and move_turtlebot3_testing.largest_move(recent) < 1e-4

        drove = _wait(lambda: moved() >= stops_c.get('min_drive', 0.5), run.deadline, 'driving', run.node)
        if not drove:
            distance = moved()
            run.stop()
            failure = run.not_running(expected) if not watch.copy('commands') else Outcome(
                False, 'expected %s; seen: the robot moved %.2f m' % (expected, distance), run.node.explain())
            return {'avoid_stops': failure,
                    'avoid_stays': Outcome(False, 'not checked: the robot did not drive')}
        stopped = _wait(lambda: stopped_for(1.0), run.deadline, 'a stop')
        first_stop = watch.copy('poses')[-1]
        if not stopped:
            run.stop()
            hints = run.node.explain()
            return {'avoid_stops': Outcome(False, 'expected %s; seen: it did not stop (drove %.2f m, '
                                           'front beam %.2f m, %d collisions)' % (
                                               expected, moved(), watch.front_range(), watch.collisions or 0), hints),
                    'avoid_stays': Outcome(False, 'not checked: the robot did not stop')}
        stay = stays_c.get('stay_seconds', 5)
        _wait(lambda: watch.now() >= first_stop[0] + stay, run.deadline, 'simulated time')
        after = watch.poses_since(first_stop[0])
        fronts = sorted(scan.ranges[0] for scan in watch.copy('scans')[-max(3, int(stay * 5)):])
        front = fronts[len(fronts) // 2]
        creep = move_turtlebot3_testing.largest_move(after)
        watched = after[-1][0] - first_stop[0]
        collisions = watch.collisions or 0
        run.stop()
        hints = run.node.explain()
        outcomes = {'avoid_stops': Outcome(
            low <= front <= high, 'expected %s; seen: it drove %.2f m and stopped with the front beam at '
            '%.3f m (median over the stop)' % (expected, move_turtlebot3_testing.travelled([spawn] + after[:1]), front), hints)}
        ok = collisions == 0 and creep <= stays_c.get('max_creep', 0.11) and watched >= stay - 0.5
        outcomes['avoid_stays'] = Outcome(ok, 'expected no collision and at most %.2f m moved in the %g simulated '
                                          'seconds after the stop; seen %d collisions, %.3f m moved in %.1f s' % (
                                              stays_c.get('max_creep', 0.11), stay, collisions, creep, watched), hints)
        return outcomes
    finally:
        run.stop()


CHECKS = [(check_trajectory, 'trajectory.py', ['trajectory_rate', 'trajectory_circle']),
          (check_laser_data, 'laser_data.py', ['laser_data']),
          (check_avoid_obstacle, 'avoid_obstacle.py', ['avoid_stops', 'avoid_stays'])]


def run_checks(session):
    return run_each(session, CHECKS)
