"""The TurtleBot3 lab (seed 001): trajectory.py, laser_data.py, avoid_obstacle.py on fake_tb3, with
the checks of course_checks that move_turtlebot3's own tests use."""
import errno
import functools
import json
import math
import os

import rospy
from geometry_msgs.msg import Twist, Vector3

from course_checks import driving, laser, callers
from course_checks.robot import SIMULATOR, RobotWatch, largest_move, node_names, travelled
from course_checks.verdict import Verdict
from course_common.waiting import Deadline
from course_grader import bags, feedback
from course_grader.labs.common import LabRun, StudentNode, criteria_of, drawn, faked, run_each, will_run
from course_grader.wall_limit import NODES
from course_common.processes import together
from course_common.waiting import poll_until

# What fake_tb3's world.launch gives the node beside a run's own settings.
LAUNCH_DEFAULTS = {'cmd_vel_timeout': 0, 'clamp_speed': False, 'picture_png': '', 'robots': []}
# Wall seconds at most for the messages of a run's last moments to be heard once it has stopped.
DRAIN_SECONDS = 2.0
# fake_tb3 as far as it goes without its parameters: its modules imported (half of its start), then
# it waits until the FIFO named by its first argument is opened for writing, which only the trusted
# side can do (the FIFO lies in its own folder), once the run's parameters are set. What the grader
# writes into it are settings no node can read (fake_tb3.put_back), unlike the master's parameters.
# It ends when the session that started it is gone (its parent changes): a session killed with
# SIGKILL stops nothing it started, and its prepared fake_tb3 waited on the FIFO for ever.
PREPARED_FAKE_TB3 = ('import os, sys, threading, time\n'
                     'def end_with_the_session(session=os.getppid()):\n'
                     '    while os.getppid() == session:\n'
                     '        time.sleep(0.5)\n'
                     '    os._exit(1)\n'
                     'threading.Thread(target=end_with_the_session, daemon=True).start()\n'
                     'from fake_tb3.node import main\nwith open(sys.argv[1]) as go:\n'
                     '    settings = go.read()\nmain(settings)\n')


class PreparedSimulator:
    """fake_tb3 of one run, started ahead of it (as the run before stops)."""

    def __init__(self, session, log_name):
        self.log_name = log_name
        self.fifo = session.log_path('.%s.go' % log_name)
        # What fake_tb3 did, as it tells it: the evidence of the run (course_common.sim_record).
        self.record = session.record_path(log_name)
        self.discard_fifo()   # of a simulator prepared before for this run, which never ran
        os.mkfifo(self.fifo, 0o600)
        # Started as fake_tb3_node would be, with the parameters world.launch would set (roslaunch's
        # own start and stop cost about a second each per run).
        try:
            self.launch = session.trusted(['/usr/bin/python3', '-c', PREPARED_FAKE_TB3, self.fifo,
                                           '__name:=' + SIMULATOR.lstrip('/')], log_name,
                                          record=self.record)
        except BaseException:   # no process or thread left in the sandbox (a fork bomb of the run before)
            self.discard_fifo()
            raise

    def _let_go(self, settings):
        try:
            go = os.open(self.fifo, os.O_WRONLY | os.O_NONBLOCK)
        except OSError as error:
            if error.errno != errno.ENXIO:
                raise
            return False   # not waiting on the FIFO yet (still importing)
        try:
            os.write(go, settings.encode())   # a few bytes into an empty pipe: all at once
        finally:
            os.close(go)
        return True

    def start(self, seconds, settings=''):
        """Let it run (its parameters are set), with the grader's settings (JSON text); the Launch.
        False from ended() when it could not."""
        poll_until(lambda: self.launch.ended() or self._let_go(settings), seconds)
        self.discard_fifo()
        return self.launch

    def discard_fifo(self):
        if os.path.lexists(self.fifo):
            os.remove(self.fifo)


class Simulators:
    """The fake_tb3 of each run ahead: the first run's while the package builds (nothing of the
    student's runs then), the others once the first run is under way (its node started: the rest of
    the run leaves the processor mostly idle, where the build does not), or each while the run
    before stops when they could not be started then."""

    def __init__(self, session, scripts):
        self.session = session
        self.logs = ['sim_%s.txt' % script.split('.')[0] for script in scripts]
        self.ready = []   # PreparedSimulator, in the order of the runs

    def prepare_next(self):
        if not self.ready and self.logs:
            self.ready.append(PreparedSimulator(self.session, self.logs[0]))
            self.logs.pop(0)

    def prepare_all(self):
        """Every run's fake_tb3 still to come started now, each waiting for its run."""
        while self.logs:
            self.ready.append(PreparedSimulator(self.session, self.logs[0]))
            self.logs.pop(0)

    def take(self):
        if self.ready and self.ready[0].launch.ended():   # prepared beside a fork bomb, say: again
            self.ready[0].discard_fifo()
            self.logs.insert(0, self.ready.pop(0).log_name)
        self.prepare_next()
        return self.ready.pop(0) if self.ready else None

    def stop(self):
        """Those prepared for runs that did not come (after one that broke down, or a build that failed)."""
        together(*[functools.partial(self._discard, prepared) for prepared in self.ready] or [lambda: None])
        self.ready = []

    @staticmethod
    def _discard(prepared):
        prepared.launch.stop(15)
        prepared.discard_fifo()


def static_checks(session):
    """The scripts are executable, with a #! line that starts Python 3."""
    criterion = session.rubric.criterion('executable')
    problems, missing = [], []
    for name in criterion['scripts']:
        path = session.script(name)
        if path is None:
            missing.append(name)
        else:
            problems += feedback.script_problems(path, session.relative(path), package=session.rubric.package)
    if missing:
        problems.insert(0, 'missing: %s' % ', '.join(missing))
    if problems:
        return {'executable': Verdict(False, 'expected `rosrun %s SCRIPT` to be able to start each '
                                      'script; seen: %s' % (session.rubric.package, problems[0]), problems[1:])}
    return {'executable': Verdict(True, 'all executable, with a Python 3 #! line')}


class Run:
    """The simulator and one of the student's nodes on it, watched, stopped at the end."""

    def __init__(self, session, simulators, script, picture=None, grader_settings=None, **sim_args):
        self.session = session
        self.simulators = simulators
        self.stopped = False
        self.sim_ended = False
        self.name = os.path.splitext(script)[0]   # of its bag, <name>.bag (course_grader.bags)
        self.marks = bags.Marks()   # the moments the checks judged
        self.entries = []     # what fake_tb3 recorded, once it stopped
        self.scene = {'world': sim_args.get('world'),
                      'model': sim_args.get('model') or os.environ.get('TURTLEBOT3_MODEL') or 'burger'}
        prepared = simulators.take()
        self.sim_log = prepared.log_name
        self.record = prepared.record
        # Its waits read fake_tb3's record (a few new lines each time): cheap enough to look every
        # 10 ms, and each of the run's seven waits then ends 20 ms sooner on average than at 50 ms.
        self.deadline = Deadline(session.rubric.limits['run_seconds'], poll=0.01)
        self.watch = RobotWatch(record=self.record)
        if picture:
            sim_args['picture_png'] = session.picture(picture)
        # fake_tb3 is the course's: it runs on the trusted side, with the course's environment, and
        # with no parameter a node of the submission set in an earlier run (a rate, say).
        if rospy.has_param(SIMULATOR):
            rospy.delete_param(SIMULATOR)
        rospy.set_param('/use_sim_time', True)
        for name, value in sorted(dict(LAUNCH_DEFAULTS, **sim_args).items()):
            rospy.set_param('%s/%s' % (SIMULATOR, name), value)
        self.sim = prepared.start(self.deadline.left(), json.dumps(grader_settings) if grader_settings else '')
        # The node starts once the simulator runs: a submission that takes every process or the
        # processor from the start has not kept fake_tb3 from starting (its nodes never start).
        if not self.deadline.wait(self.watch.running, gave_up=self.sim.ended):
            self.sim.stop(15)
            raise RuntimeError('the simulator did not start (see %s)' % self.sim_log)
        self.node = StudentNode(session, script)

    def under_way(self):
        """The student's node does its part: the simulators of the runs after this one start now
        (Simulators), unless the sandbox has no process left for them (each run prepares its own then)."""
        try:
            self.simulators.prepare_all()
        except OSError:
            pass

    def not_running(self, expected):
        """An outcome for a node that did not do anything: expected, and why (hints)."""
        hints = self.node.explain()
        return Verdict(False, 'expected %s; seen: %s' % (expected, hints[0] if hints else 'nothing'), hints[1:])

    def mark(self, t, what, criterion):
        """A moment the checks judged, at `t` simulated seconds (kept beside the run's bag)."""
        self.marks.add(t, what, criterion)

    def judged(self, outcomes):
        """The outcomes, judged on fake_tb3's own record, unless the run was not the simulator's
        own doing: then they fail, naming who did what (a node of the submission that published on
        odom, scan or clock, a node that called fake_tb3's service, or a simulator that a node shut
        down). The moments marked are kept beside the run's bag, with each collision of a run
        that judges avoid_stays."""
        if 'avoid_stays' in outcomes:
            for t, count in bags.collisions(self.entries):
                self.mark(t, 'collision %d' % count, 'avoid_stays')
        self.session.keep_marks(self.name, self.marks)
        impostors = self.watch.impostors()
        if impostors:
            return faked(outcomes, impostors, SIMULATOR)
        calls = self.watch.service_calls()
        if calls:
            return callers.called(outcomes, calls)
        if self.sim_ended:
            reason = ('not judged: the simulator stopped during the run, before the grader stopped it (see %s)'
                      % self.sim_log)
            return {criterion_id: Verdict(False, reason) for criterion_id in outcomes}
        return outcomes

    def stop(self):
        if self.stopped:
            return
        self.stopped = True
        self.sim_ended = self.sim.ended()
        try:
            self.simulators.prepare_next()
        except OSError:
            pass   # the sandbox has no process left now: the next run prepares its own when it starts
        # The node and the simulator stop together; fake_tb3 writes its picture before it leaves the
        # ROS graph, and what is left of either then is its exit (not waited for).
        together(self.node.stop, functools.partial(self.sim.stop, 15, lambda: SIMULATOR not in node_names()))
        # Then everything fake_tb3 recorded is read: at 10x the scans a node printed last may have
        # been sent just before the stop.
        self.watch.drain(DRAIN_SECONDS)
        self.watch.close()
        if os.path.exists(self.record):   # read: kept as the run's bag, it would only fill the trusted side's disk
            try:
                self.entries = bags.read_record(self.record)
            except OSError:   # kept or not, the run's verdicts stand (keep_run notes a bag it cannot make)
                self.entries = []
            self.session.keep_run(self.name, lambda: bags.fake_tb3_messages(self.entries, **self.scene))
            os.remove(self.record)


def check_trajectory(session, simulators):
    rate_c = session.rubric.criterion('trajectory_rate')
    circle_c = session.rubric.criterion('trajectory_circle')
    linear, angular = rate_c['linear'], rate_c['angular']
    run = Run(session, simulators, rate_c['script'], picture='trajectory.png', world=rate_c['world'], x_pos=rate_c['x_pos'],
              y_pos=rate_c['y_pos'], noise_stddev=rate_c['noise_stddev'], real_time_factor=rate_c['real_time_factor'])
    try:
        watch = run.watch
        expected_rate = '%s: Twist linear.x %g m/s, angular.z %g rad/s on cmd_vel at %g Hz' % (
            run.node.name, linear, angular, rate_c['rate_hz'])
        if not run.deadline.wait(lambda: watch.copy('commands'), gave_up=run.node.ended):
            run.stop()
            failure = run.not_running(expected_rate)
            return run.judged({'trajectory_rate': failure,
                    'trajectory_circle': Verdict(False, 'not checked: %s published nothing' % run.node.name)})
        run.under_way()   # the first run: the other runs' simulators start now
        start = watch.now()
        period = 2 * math.pi / abs(angular) if angular else 10.0
        watched = circle_c['periods'] * period + 2
        run.deadline.wait(lambda: watch.now() >= start + watched)
        seen_for = watch.now() - start
        poses = watch.poses_since(start)
        commands = [(t, lin, ang) for t, lin, ang in watch.copy('commands') if t is not None and t >= start]
        run.stop()
        hints = run.node.explain()
        outcomes = {}
        # Rate and values of the commands, in simulated time.
        kept = driving.commands_kept(commands, seen_for, linear, angular, rate_c['speed_tolerance'],
                                     rate_c['rate_hz'], rate_c['rate_tolerance'])
        outcomes['trajectory_rate'] = Verdict(kept.passed, 'expected %s; seen %s' % (expected_rate, kept.reason), hints)
        # The circle of those commands, from the spawn pose.
        expected_radius = abs(linear / angular) if angular else float('inf')
        spawn = (rate_c['x_pos'], rate_c['y_pos'])
        expected_circle = 'a circle of radius %.2f m through the spawn pose (%g, %g)' % ((expected_radius,) + spawn)
        driven = driving.circle_through(poses, expected_radius, spawn, circle_c['radius_tolerance'],
                                        circle_c['min_travel'])
        outcomes['trajectory_circle'] = Verdict(driven.passed, 'expected %s (within %.2f m); seen %s' % (
            expected_circle, circle_c['radius_tolerance'] * expected_radius, driven.reason), hints)
        run.mark(start, 'the circle watched from here, for %.1f simulated s' % seen_for, 'trajectory_circle')
        if poses:
            closing = [pose for pose in poses if pose[0] >= start + period / 2] or poses[-1:]
            back = min(closing, key=lambda pose: math.hypot(pose[1] - spawn[0], pose[2] - spawn[1]))
            run.mark(back[0], 'closest back to the spawn pose: %.2f m from it' % math.hypot(
                back[1] - spawn[0], back[2] - spawn[1]), 'trajectory_circle')
        run.mark(start + seen_for, 'the circle judged: %s' % driven.reason, 'trajectory_circle')
        return run.judged(outcomes)
    finally:
        run.stop()


def check_laser_data(session, simulators):
    criterion = session.rubric.criterion('laser_data')
    beams = criterion['beams']
    needed = criterion['blocks']
    run = Run(session, simulators, criterion['script'], world=criterion['world'], x_pos=criterion['x_pos'],
              y_pos=criterion['y_pos'], noise_stddev=criterion['noise_stddev'],
              noise_seed=criterion['noise_seed'], real_time_factor=criterion['real_time_factor'])
    # The grader turns the robot in place, from a moment its own timing sets, at a speed and in a
    # direction drawn for this grading: no two scans in a row are alike, nor the scans of two
    # gradings (a printout stored from one fits no other), so only a node that reads each scan prints it.
    turn_speed = drawn(criterion['turn_speed'], either_way=True)
    turn = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
    try:
        turn.publish(Twist(angular=Vector3(z=turn_speed)))
        expected = ('%s prints, for every scan as it comes, ========== and the labels s1 [0] ... s5 [359] each '
                    'followed by the range of that beam (%s)' % (run.node.name, ', '.join(map(str, beams))))
        grader = rospy.get_name()

        def timed_blocks():
            return laser.timed_blocks(run.node.launch.timed_lines() if run.node.launch else [])

        def printed_since_turn():
            """As many blocks as needed printed once fake_tb3 applied the turn (judged from there on,
            below: a block of before, on a machine that delayed the turn, does not count)."""
            turned = run.watch.first_command_of(grader)
            return turned is not None and len(laser.since(turned, timed_blocks(), run.watch.scan_entries())[0]) >= needed
        run.deadline.wait(printed_since_turn, gave_up=run.node.ended)
        blocks = timed_blocks()
        run.stop()
        scans = run.watch.scan_entries()   # (time sent, scan) of every scan fake_tb3 sent, up to its stop
        hints = run.node.explain()
        if not blocks:
            if not hints:
                hints = ['%d lines printed, none in the form of the slide (first: %r)' % (
                    len(run.node.lines), run.node.lines[0] if run.node.lines else '')]
            return run.judged({'laser_data': Verdict(False, 'expected %s; seen: %s' % (expected, hints[0]), hints[1:])})
        # The turn is what no stored printout can follow: a node that stopped it (its own cmd_vel)
        # printed scans of a robot standing still, which are the same in every grading.
        stoppers = run.watch.command_senders(but=grader)
        if stoppers:
            return run.judged({'laser_data': Verdict(False, 'expected %s; seen: %s sent velocity commands while the '
                                                     'grader turned the robot (laser_data.py only prints the scans)'
                                                     % (expected, ', '.join(stoppers)), hints)})
        # Nor a node that cut the grader's turn off before fake_tb3 heard it (a subscriber can be told
        # through the ROS APIs that a publisher is gone): only scans fake_tb3 sent after it applied
        # the turn, by its own record, are judged.
        turned = run.watch.first_command_of(grader)
        if turned is None:
            return run.judged({'laser_data': Verdict(False, 'expected %s; seen: fake_tb3 never applied the grader\'s '
                                                     'turn (its record holds no command of the grader), so no scan '
                                                     'it sent can be told from a stored one' % expected, hints)})
        run.mark(turned, 'fake_tb3 turns the robot at %.2f rad/s: the scans from here are judged' % turn_speed,
                 'laser_data')
        printed_before = len(blocks)
        blocks, scans = laser.since(turned, blocks, scans)
        if not blocks:
            return run.judged({'laser_data': Verdict(False, 'expected %s; seen: %d scans printed, none once fake_tb3 '
                                                     'turned the robot (%.1f simulated s)'
                                                     % (expected, printed_before, turned), hints)})
        # The window in scans too, as many as the simulator sends in it at its pace (50 in 1 s at
        # 10x): a machine paused between a scan and its block sends none meanwhile.
        window_scans = int(round(criterion['print_window'] * criterion['real_time_factor'] * driving.SCAN_HZ))
        printed = laser.printed_in_time(blocks, scans, beams, needed, criterion['print_window'], window_scans)
        return run.judged({'laser_data': Verdict(printed.passed, 'expected %s; seen %s' % (expected, printed.reason),
                                                 hints)})
    finally:
        turn.unregister()   # latched: the next run's fake_tb3 must not hear it
        run.stop()


def check_avoid_obstacle(session, simulators):
    stops_c = session.rubric.criterion('avoid_stops')
    stays_c = session.rubric.criterion('avoid_stays')
    # The grader's second start (fake_tb3.put_back): once the robot stood still for a while it is put
    # back along its heading, at a moment and by a distance drawn here for this grading and given to
    # fake_tb3 where no node can read them. A node that answers its scans drives and stops again;
    # one that drives by the clock, tuned to the spawn pose, cannot know when or how far.
    put_back = {'min_drive': stops_c['min_drive'], 'after': drawn(stops_c['put_back_after']),
                'distance': drawn(stops_c['put_back_distance'])}
    run = Run(session, simulators, stops_c['script'], picture='avoid_obstacle.png',
              grader_settings={'put_back': put_back},
              world=stops_c['world'], x_pos=stops_c['x_pos'],
              y_pos=stops_c['y_pos'], noise_stddev=stops_c['noise_stddev'],
              noise_seed=stops_c['noise_seed'], real_time_factor=stops_c['real_time_factor'],
              lock_step=stops_c['lock_step'])
    try:
        watch = run.watch
        low, high = stops_c['front_min'], stops_c['front_max']
        react = stops_c['react_seconds']
        expected = ('%s drives at least %.1f m and stops with its front beam between %.2f and %.2f m, and once '
                    'the grader puts it back, drives again within %g s and stops so again' % (
                        run.node.name, stops_c['min_drive'], low, high, react))
        spawn = watch.copy('poses')[0]

        def moved():
            return largest_move([spawn] + watch.copy('poses'))

        drove = run.deadline.wait(lambda: moved() >= stops_c['min_drive'], gave_up=run.node.ended)
        if not drove:
            distance = moved()
            run.stop()
            failure = run.not_running(expected) if not watch.copy('commands') else Verdict(
                False, 'expected %s; seen: the robot moved %.2f m' % (expected, distance), run.node.explain())
            return run.judged({'avoid_stops': failure,
                    'avoid_stays': Verdict(False, 'not checked: the robot did not drive')})
        stopped = run.deadline.wait(lambda: driving.stopped_for(watch.copy('poses'), stops_c['stopped_seconds']))
        # The stay is watched from the stop itself: the standing still that told it counts too.
        first_stop = driving.still_since(watch.copy('poses'))
        if not stopped:
            run.stop()
            hints = run.node.explain()
            run.mark(watch.now(), 'not stopped by the end of the run (front beam %.2f m)' % watch.front_range(),
                     'avoid_stops')
            return run.judged({'avoid_stops': Verdict(False, 'expected %s; seen: it did not stop (drove %.2f m, '
                                           'front beam %.2f m, %d collisions)' % (
                                               expected, moved(), watch.front_range(), watch.collisions or 0), hints),
                    'avoid_stays': Verdict(False, 'not checked: the robot did not stop')})
        stay = stays_c['stay_seconds']
        run.deadline.wait(lambda: watch.now() >= first_stop[0] + stay)
        # The first stop and its stay, up to the put-back (which may come a tick before the stay's end).
        put = watch.put_back()
        stay_end = min(first_stop[0] + stay, put[0]) if put else first_stop[0] + stay
        after = [pose for pose in watch.poses_since(first_stop[0]) if pose[0] < stay_end]
        front = driving.front_at_stop([scan for scan in watch.copy('scans') if scan.header.stamp.to_sec() < stay_end],
                                      stay, low, high)
        run.mark(first_stop[0], 'stopped after %.2f m: %s' % (travelled([spawn] + after[:1]), front.reason),
                 'avoid_stops')
        again = second_start(run, put_back, first_stop[0], react, low, high, stops_c['stopped_seconds'])
        run.stop()
        hints = run.node.explain()
        stayed = driving.stayed(after, watch.collisions or 0, stays_c['max_creep'], stay)
        outcomes = {'avoid_stops': Verdict(front.passed and again.passed, 'expected %s; seen: it drove %.2f m and %s; %s' % (
            expected, travelled([spawn] + after[:1]), front.reason, again.reason), hints)}
        run.mark(after[-1][0] if after else first_stop[0], 'the stay judged: %s' % stayed.reason, 'avoid_stays')
        outcomes['avoid_stays'] = Verdict(stayed.passed, 'expected no collision and at most %.2f m moved in the %g '
                                          'simulated seconds after the stop; seen %s' % (
                                              stays_c['max_creep'], stay, stayed.reason), hints)
        return run.judged(outcomes)
    finally:
        run.stop()


def second_start(run, put_back, stopped_at, react, low, high, stopped_seconds):
    """What the robot did once fake_tb3 put it back (its record tells when and where): a Verdict that
    it drove off within `react` simulated s and stopped again with its front beam between low and high."""
    watch = run.watch
    # It stands still from its stop for `after` s at least (longer when it crept meanwhile).
    run.deadline.wait(lambda: watch.put_back() or watch.now() >= stopped_at + 2 * put_back['after'] + 2,
                      gave_up=run.node.ended)
    put = watch.put_back()
    if put is None:
        if run.node.ended():
            return Verdict(False, '%s ended before the grader could put the robot back' % run.node.name)
        return Verdict(False, 'the grader puts the robot back once it stood still for %.1f s, and it never '
                       'stood still that long' % put_back['after'])
    at, where = put
    distance = math.hypot(where['to_x'] - where['x'], where['to_y'] - where['y'])
    told = 'put back %.2f m after %.1f s standing still' % (distance, at - where['still_since'])
    run.mark(at, 'the grader puts the robot back %.2f m: it must drive and stop again' % distance, 'avoid_stops')

    def judged():
        off = driving.drove_off(watch.copy('poses'), at, (where['to_x'], where['to_y']))
        if off is None:
            return watch.now() >= at + react
        return off > at + react or driving.stopped_for(watch.poses_since(off), stopped_seconds)
    run.deadline.wait(judged, gave_up=run.node.ended)
    off = driving.drove_off(watch.copy('poses'), at, (where['to_x'], where['to_y']))
    if off is None:
        return Verdict(False, '%s, it did not drive again within %g s (a node that answers its scans drives '
                       'on the next one)' % (told, react))
    if off > at + react:
        return Verdict(False, '%s, it drove again only %.1f s later (within %g s expected: a node that answers '
                       'its scans drives on the next one)' % (told, off - at, react))
    if not driving.stopped_for(watch.poses_since(off), stopped_seconds):
        return Verdict(False, '%s, it drove again and did not stop (front beam %.2f m)' % (told, watch.front_range()))
    stop = driving.still_since(watch.copy('poses'))
    front = driving.front_at_stop([scan for scan in watch.copy('scans') if scan.header.stamp.to_sec() >= stop[0]],
                                  stopped_seconds, low, high)
    run.mark(stop[0], 'stopped again after %.2f m: %s' % (travelled(watch.poses_since(at)[:1] + [stop]), front.reason),
             'avoid_stops')
    return Verdict(front.passed, '%s, it drove again %.1f s later and %s' % (told, off - at, front.reason))


# Decided without a run: builds by the session's build, executable by static_checks.
STATIC_CRITERIA = {
    'builds': (),
    'executable': ('scripts',),
}
# The settings of a run's fake_tb3, in the criterion its check starts the run with.
SIMULATION = ('script', 'world', 'x_pos', 'y_pos', 'noise_stddev', 'noise_seed', 'real_time_factor')
# The lab's runs after the build, in order: each script on fake_tb3 (its check gets the Simulators).
RUNS = (
    LabRun('trajectory.py', check_trajectory, {
        'trajectory_rate': ('script', 'world', 'x_pos', 'y_pos', 'noise_stddev', 'real_time_factor', 'linear',
                            'angular', 'speed_tolerance', 'rate_hz', 'rate_tolerance'),
        'trajectory_circle': ('radius_tolerance', 'periods', 'min_travel'),
    }, (NODES,)),
    LabRun('laser_data.py', check_laser_data, {
        'laser_data': SIMULATION + ('beams', 'blocks', 'turn_speed', 'print_window'),
    }, (NODES,)),
    LabRun('avoid_obstacle.py', check_avoid_obstacle, {
        'avoid_stops': SIMULATION + ('lock_step', 'min_drive', 'stopped_seconds', 'front_min', 'front_max',
                                     'put_back_after', 'put_back_distance', 'react_seconds'),
        'avoid_stays': ('stay_seconds', 'max_creep'),
    }, (NODES,)),
)
CRITERIA = criteria_of(STATIC_CRITERIA, RUNS)
# The settings that are [low, high] bounds of a number drawn at each grading (rubric.check_drawn).
DRAWN = (('laser_data', 'turn_speed'), ('avoid_stops', 'put_back_after'), ('avoid_stops', 'put_back_distance'))


def prepare(session):
    """While the package builds: the first run's fake_tb3 started and importing (half of its start),
    then waiting for its run (PreparedSimulator). Returns what stops those no run took."""
    session.simulators = Simulators(session, [run.name for run in will_run(session, RUNS)])
    try:
        session.simulators.prepare_next()
    except OSError:
        pass   # no process left: each run prepares its own when it starts
    return session.simulators.stop


def run_checks(session):
    simulators = getattr(session, 'simulators', None) or Simulators(session, [run.name for run in will_run(session, RUNS)])
    try:
        return run_each(session, RUNS, simulators=simulators)
    finally:
        simulators.stop()
