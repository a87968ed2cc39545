"""The lab report's exercises (seed 002): ros_exercises' launch files exercise1..5 on the course's
turtlesim (started by the grader in place of the launch file's own, labs.turtlesim_runs), with the
checks of course_checks that ros_exercises' own tests use."""
import collections
import functools
import random
import re
import threading
import time

import rospy
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Int32

from course_checks import figures, rates, turtle
from course_checks.robot import node_names
from course_checks.verdict import Verdict
from course_common.waiting import Deadline, wait_in_slices
from course_common.timing import Pacer
from course_grader import feedback
from course_grader.labs.common import LabRun, criteria_of, drawn, run_each
from course_grader.labs.turtlesim_runs import SimulatedClock, TurtlesimLaunch, describe_launches
from course_grader.wall_limit import NODES, READING

NUMBER = r'(-?\d+\.\d+)'
# The grader's next digit to exercise 1's subscriber after this, if the last is not printed yet: a
# subscriber that takes each message in a loop of its own (ros::spinOnce at 1 Hz and more) and keeps
# one (queue of 1) hears each digit. Only a subscriber that does not print what it hears waits it out.
SEND_SECONDS = 1.5
PRINT_SECONDS = 3.0   # then the subscriber's last lines may take this long
UNHEARD_SECONDS = 1.0   # after a line printed before anything subscribed, how long it may still take to subscribe


def _printed(run, pattern):
    return [match.groups() for match in (re.search(pattern, line) for line in run.lines) if match]


def _args(session, shape):
    """The arguments exercise5.launch is run with for `shape`."""
    criterion = session.rubric.criterion(shape)
    return ['shape:=' + shape, 'side:=%g' % criterion['side'], 'speed:=%g' % criterion['speed'],
            'turn_speed:=%g' % criterion['turn_speed']]


def _exercise1_args(rate_c):
    """The arguments exercise1.launch is run with, for the publisher and for the subscriber alone
    (one reading of the file serves both: describe_launches' key)."""
    return ['rate:=%g' % rate_c['rate'], 'id:=' + str(rate_c['id_number'])]


def _launches(session):
    """Each launch file the lab runs, with its arguments."""
    rate_c = session.rubric.criterion('publisher_rate')
    return [(rate_c['launch_file'], _exercise1_args(rate_c))] + [
        (session.rubric.criterion(criterion_id)['launch_file'], []) for criterion_id in
        ('listener_prints_pose', 'circle', 'spawn_kill')] + [
        (session.rubric.criterion(shape)['launch_file'], _args(session, shape)) for shape in ('square', 'triangle')]


class Exercise(TurtlesimLaunch):
    """One of the student's launch files, run as the lab asks (its turtlesim on the trusted side, at
    the criterion's real-time factor: without one, on the wall clock), logged to <name>.log, stopped
    at the end; turtlesim's window is kept as `picture`. `only`: that executable's node of the file
    alone (TurtlesimLaunch)."""

    def __init__(self, session, criterion, log_name, *args, picture=None, lock_step=False, only=None):
        self.deadline = Deadline(session.rubric.limits['run_seconds'])
        # How far the turtle drives between poses heard; a criterion without one runs on the wall clock.
        self.real_time_factor = criterion.settings.get('real_time_factor')
        super().__init__(session, criterion['launch_file'], list(args), log_name, picture=picture,
                         real_time_factor=self.real_time_factor, lock_step=lock_step, only=only)

    def on_interface(self, recorder, name):
        """A failing verdict when a node called a teleport or /reset, or the turtle moved where no
        velocity took it (as turtlesim recorded it); None when the simulator alone moved it. (A node
        that published on the pose topic fails the run's criteria: TurtlesimLaunch.judged.)"""
        return turtle.no_unused_calls(self.service_calls()) or turtle.no_jumps(recorder, name, self.real_time_factor)

    def wait(self, condition, seconds=None, poll=0.05):
        """condition() within `seconds` (the run's time left at most); False as soon as the launch ended."""
        return self.deadline.wait(condition, seconds, gave_up=self.run.ended, poll=poll)

    def printed(self, pattern):
        return _printed(self.run, pattern)

    def nothing(self, what):
        if self.unread:
            return 'expected `%s` to %s; seen: %s' % (self.command, what, self.unread)
        return 'expected `%s` to %s; seen: %s' % (self.command, what, feedback.paste_run_error(
            self.session.rubric.package, self.run.output) or self.run.error_lines())


class HeldClockDriver:
    """/clock for exercise 1, published by the grader: rates.HeldClock's time at real_time_factor,
    holding at most PATIENCE wall seconds for each message due (then on until the next), creeping
    over the first `settling` messages and before each hold, standing still once for STILL_SECONDS
    after `stand_still_after` messages, and each message on `topic` kept with its stamp on that
    clock and the wall time it was heard at."""
    STEP_NS = 4000000   # 250 per simulated second, as turtlesim's /clock
    PATIENCE = 3.0      # wall seconds a message due may take: a publisher kept that long from the processor
    LATENCIES = 10      # messages whose way from a step to here decides how long the clock creeps (rates.creep_seconds)
    STILL_SECONDS = 1.0   # wall seconds the clock stands still once (rates.HeldClock.standing_still)

    def __init__(self, topic, message_class, period, real_time_factor, settling, stand_still_after=None):
        self.clock = rates.HeldClock(int(round(period * 1e9)), self.STEP_NS, settling, stand_still_after)
        self.lock = threading.Lock()
        self.heard_one = threading.Event()
        self.stopped = threading.Event()
        self.entries = []   # (stamp on the clock, message)
        self.heard_at = []   # the wall time (time.monotonic()) each of entries was heard at
        self.still = None   # (seconds, [wall time of each message heard]) while the clock stood still
        self.latencies = collections.deque(maxlen=self.LATENCIES)   # wall seconds from a step to its message heard
        self.clock_pub = rospy.Publisher('/clock', Clock, queue_size=10)
        self.subscriber = rospy.Subscriber(topic, message_class, self._heard, queue_size=1000)
        self.pacer = Pacer(real_time_factor, time.monotonic())
        self.stepped_at = time.monotonic()   # when the last step was published
        self.started_at = time.monotonic()
        self.crept_before_first = 0.0   # wall seconds the clock crept before the first message came
        self.waited_at_first = None     # waited_for_first() when the first message came
        self.thread = threading.Thread(target=self._run, name='held-clock', daemon=True)
        self.thread.start()

    def now(self):
        return self.clock.now_ns / 1e9

    def waited_for_first(self):
        """Wall seconds the publisher has had for its first message: since the clock started, less
        those it crept before that message. The creeps are the grader's own slowness (10 ms a step of
        4 ms: 2.7 s of wall time a simulated second at a real-time factor of 5), and a publisher that
        sleeps on the clock before it publishes would otherwise lose to them."""
        with self.lock:
            return self._waited()

    def _waited(self):   # with self.lock held
        return time.monotonic() - self.started_at - self.crept_before_first

    def wait_for_first(self, wait, seconds, started):
        """Whether a first message came within `seconds` of waited_for_first(), or of wall time while
        started() says no node of the run has started (one that has not by then never will);
        wait(condition) is the run's own wait (its deadline, its end)."""
        def came_or_given_up():
            return (self.entries or self.waited_for_first() > seconds
                    or (time.monotonic() - self.started_at > seconds and not started()))
        return wait(came_or_given_up) and bool(self.entries)

    def _heard(self, message):
        with self.lock:
            self.entries.append((self.clock.heard(), message))
            self.heard_at.append(time.monotonic())
            if self.waited_at_first is None:
                self.waited_at_first = self._waited()
        self.heard_one.set()

    def _run(self):
        while True:
            self.heard_one.clear()
            if self.stopped.is_set():   # after the clearing: close() sets the event after the flag
                return
            with self.lock:
                now_ns = self.clock.next_ns()
                holding, creeping, settled = self.clock.holding(), self.clock.creeping(), self.clock.settled()
                standing_still = self.clock.standing_still()
                heard_any = self.clock.heard_count > 0
            if now_ns is None:
                if holding and not self._heard_within(self.PATIENCE):
                    with self.lock:
                        if self.clock.holding():
                            self.clock.give_up()
                continue
            delay = self.pacer.due(now_ns) - time.monotonic()
            if delay > 0:
                self.stopped.wait(delay)
            self.pacer.reached(now_ns, time.monotonic())
            self.clock_pub.publish(Clock(rospy.Time(0, now_ns)))
            self.stepped_at = time.monotonic()
            if creeping:
                crept_from = time.monotonic()
                self._heard_within(rates.creep_seconds(self.latencies, settled, heard_any))
                self.pacer.hold(now_ns, time.monotonic())
                if not heard_any:
                    with self.lock:
                        self.crept_before_first += time.monotonic() - crept_from
            if standing_still:
                self._stand_still()

    def measured(self, count, window):
        """Whether there is enough to judge: `count` messages came, or `window` simulated seconds
        passed since the first (a slower publisher is measured over what came); not while the clock
        stands still (rates.HeldClock.standing_still), when a publisher timed by the wall clock may
        send many messages, judged once it is over."""
        entries = self.entries
        enough = len(entries) >= count or bool(entries and self.now() - entries[0][0] > window)
        return enough and not (self.clock.stood_still and self.still is None)

    def _stand_still(self):
        """Keeps the clock where it is for STILL_SECONDS of the grader's own time (wait_in_slices),
        noting the wall times of the messages heard meanwhile (`still`)."""
        with self.lock:
            first = len(self.entries)
        wait_in_slices(self.stopped.wait, self.STILL_SECONDS)
        with self.lock:
            self.still = (self.STILL_SECONDS, self.heard_at[first:])
        self.pacer.hold(self.clock.now_ns, time.monotonic())

    def _heard_within(self, seconds):
        """Whether a message came within `seconds` of the grader's own time (waiting.wait_in_slices: a
        machine paused while the clock held for a message due, the publisher with it, does not
        count against the publisher); if so, how long after the last step it was heard is one of the
        latencies (the message was due at that step, or sent at it while creeping)."""
        if not wait_in_slices(self.heard_one.wait, seconds):
            return False
        self.latencies.append(time.monotonic() - self.stepped_at)
        return True

    def close(self):
        self.stopped.set()
        self.heard_one.set()   # a clock holding for a message waits no longer (PATIENCE)
        self.thread.join()
        self.subscriber.unregister()
        self.clock_pub.unregister()


def _heard_numbers(exercise):
    """The numbers exercise 1's subscriber printed, `I heard: [n]`, in order."""
    return [int(number) for (number,) in exercise.printed(r'I heard: \[(\d+)\]')]


def check_publisher(session):
    rate_c = session.rubric.criterion('publisher_rate')
    id_number, rate, skipped = str(rate_c['id_number']), rate_c['rate'], int(rate_c['skipped'])
    count = int(rate_c['messages']) + skipped
    # The publisher's rate is judged on a simulated clock the grader publishes, which waits for each
    # message due (HeldClock) and creeps over the messages left out and before each hold: a busy
    # machine delays the publisher, never its rate.
    # Halfway through the measured messages the clock stands still for a second: a publisher timed by
    # the wall clock goes on sending, and is measured on it (a hold waits for its slower messages as
    # for ones the machine delays: at 25 Hz it was measured at 50.00 Hz).
    digits = HeldClockDriver('/ZabirovaKostyukova', Int32, 1.0 / rate, rate_c['real_time_factor'], skipped,
                             stand_still_after=skipped + int(rate_c['messages']) // 2)
    exercise = Exercise(session, rate_c, 'exercise1.log', *_exercise1_args(rate_c))
    window = 1.5 * count / rate   # simulated seconds from the first digit: a slower publisher is measured over what came
    try:
        start_seconds = session.rubric.limits['start_seconds']
        complete = (digits.wait_for_first(exercise.wait, start_seconds, lambda: node_names() - exercise.known_nodes)
                    and exercise.wait(lambda: digits.measured(count, window), start_seconds + window))
        entries = list(digits.entries)
        if len(entries) < skipped + 2:   # a rate needs two messages after those left out
            verdict = Verdict(False, exercise.nothing(
                'publish the digits of %s on /ZabirovaKostyukova; %d arrived' % (id_number, len(entries))))
        else:
            verdict = rates.publisher_verdict(
                [(stamp, digit.data) for stamp, digit in entries], skipped, count, rate, rate_c['tolerance'], id_number,
                digits.still, complete)
        return exercise.judged({'publisher_rate': verdict})
    finally:
        exercise.finish()
        digits.close()


def check_subscriber(session):
    """Exercise 1's subscriber on its own: exercise1.launch (with exercise 1's arguments) with the
    node of the subscriber's executable alone, the grader publishing in place of the publisher
    digits it draws at each run. The ID's digits are known beforehand (a node could print them
    without hearing anything), and the publisher's points are its own: these can only be heard."""
    criterion = session.rubric.criterion('subscriber_prints')
    rate_c = session.rubric.criterion('publisher_rate')
    sent = [random.SystemRandom().randrange(10) for _ in range(int(criterion['digits']))]
    grader = rospy.Publisher('/ZabirovaKostyukova', Int32, queue_size=len(sent))
    exercise = Exercise(session, criterion, 'exercise1_subscriber.log', *_exercise1_args(rate_c),
                        only=criterion['executable'])
    try:
        def subscribed():
            return grader.get_num_connections() > 0
        # A line printed before anything subscribed ends the wait too (it was not heard); the node
        # may still subscribe, and hear the grader's digits or not.
        exercise.wait(lambda: subscribed() or _heard_numbers(exercise), session.rubric.limits['start_seconds'])
        exercise.wait(subscribed, UNHEARD_SECONDS)
        if subscribed():
            # One digit at a time: the next once the last is printed (looked for every 5 ms: a
            # ROS_INFO line comes within a millisecond or two), or after SEND_SECONDS.
            for printed, digit in enumerate(sent, 1):
                grader.publish(Int32(digit))
                exercise.wait(lambda wanted=printed: len(_heard_numbers(exercise)) >= wanted, SEND_SECONDS, poll=0.005)
            exercise.wait(lambda: len(_heard_numbers(exercise)) >= len(sent), PRINT_SECONDS)
        else:
            sent = []
        if sent or _heard_numbers(exercise):
            verdict = rates.subscriber_verdict(_heard_numbers(exercise), sent)
        else:
            verdict = Verdict(False, exercise.nothing(
                'subscribe to /ZabirovaKostyukova with its %s node, run without the file\'s other nodes (the grader '
                'publishing in place of the publisher); nothing subscribed' % criterion['executable']))
        return exercise.judged({'subscriber_prints': verdict})
    finally:
        exercise.finish()
        grader.unregister()


def check_listener(session):
    criterion = session.rubric.criterion('listener_prints_pose')
    exercise = Exercise(session, criterion, 'exercise2.log')
    poses = exercise.poses('turtle1')
    line = r'x: %s, y: %s, theta: %s' % (NUMBER, NUMBER, NUMBER)
    teleop = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
    clock = None
    try:
        if not exercise.wait(lambda: exercise.printed(line), session.rubric.limits['start_seconds']):
            return exercise.judged({'listener_prints_pose': Verdict(
                False, exercise.nothing('print lines `x: .., y: .., theta: ..`'))})
        # The grader hears every pose from here on: the turtle stands still until then.
        exercise.wait(lambda: poses.count(), 10)
        # Drive the turtle as a teleop would (20 Hz of turtlesim's clock), until the listener has
        # printed it moving, on an arc drawn for this grading: poses made up from a known drive
        # (turtlesim's steps are exact) fit no other grading.
        command = Twist()
        command.linear.x, command.angular.z = drawn(criterion['linear']), drawn(criterion['angular'], either_way=True)
        clock = SimulatedClock(0.05, lambda: teleop.publish(command))
        moved = exercise.wait(lambda: any(float(x) > criterion['until_x'] for x, _, _ in exercise.printed(line)), 10)
        clock.shutdown()
        printed = exercise.printed(line)
        judged = turtle.printed_poses_published(printed, poses)
        wrong = None if judged.passed else judged.reason
        if not moved:
            wrong = 'the printed pose did not follow the turtle driven to x > %g (last printed %s)' % (
                criterion['until_x'], printed[-1],)
        verdict = Verdict(not wrong, 'expected the pose turtlesim publishes, printed as the turtle moves (the grader '
                          'drove it at %.2f m/s turning %.2f rad/s); seen %s' % (
                              command.linear.x, command.angular.z, wrong or judged.reason))
        return exercise.judged({'listener_prints_pose': exercise.on_interface(poses, 'turtle1') or verdict})
    finally:
        if clock:
            clock.shutdown()
        teleop.unregister()
        exercise.finish()


def check_circle(session):
    criterion = session.rubric.criterion('circle')
    # The node answers each pose it prints (Fig. 5 publishes in the pose callback): turtlesim waits for
    # that answer (lock step), so a machine that keeps the node waiting makes it skip no pose.
    exercise = Exercise(session, criterion, 'exercise3.log', picture='circle.png', lock_step=True)
    poses = exercise.poses('turtle1')
    radius = criterion['radius']
    try:
        if not exercise.wait(lambda: poses.count() and poses.latest().linear_velocity > 0,
                             session.rubric.limits['start_seconds']):
            return exercise.judged({'circle': Verdict(False, exercise.nothing('drive turtle1'))})
        # turtle1 starts at the middle facing +x: the centre is `radius` to its left.
        centre = (criterion['start'][0], criterion['start'][1] + radius)
        full_turn, seconds = turtle.full_turn(radius), criterion['turn_seconds']
        exercise.wait(lambda: len(turtle.moving_points(turtle.pose_array(poses))) >= full_turn, seconds)
        points = turtle.moving_points(turtle.pose_array(poses))
        if len(points) < full_turn:
            wrong, seen = '%d moving poses in %g s, fewer than a full turn (%d)' % (len(points), seconds, full_turn), None
        else:
            circled = turtle.circle(points, centre, radius, criterion['tolerance'])
            wrong, seen = (None if circled.passed else circled.reason), None
        if not wrong:
            printed = exercise.printed(r'Turtle subscriber@\[%s, %s, %s\]' % (NUMBER, NUMBER, NUMBER))
            pasted = feedback.paste_run_error(session.rubric.package, exercise.run.output)
            judged = (turtle.printed_poses_published(printed, poses) if printed
                      else Verdict(False, 'no line `Turtle subscriber@[x, y, theta]` printed%s'
                                   % ('; ' + pasted if pasted else '')))
            wrong, seen = (None, judged.reason) if judged.passed else (judged.reason, None)
        verdict = Verdict(not wrong, 'expected a circle of radius %g m around (%.2f, %.2f), with the pose '
                          'printed; seen %s' % (radius, centre[0], centre[1], wrong or 'it: ' + seen))
        _mark_circle(exercise, poses, len(points), full_turn, wrong or 'a circle of radius %g m: ' % radius + seen)
        return exercise.judged({'circle': exercise.on_interface(poses, 'turtle1') or verdict})
    finally:
        exercise.finish()


def _mark_circle(exercise, poses, judged, full_turn, seen):
    """The circle's moments: turtle1 starts to drive, closes its full turn (the `full_turn`-th
    moving pose), and the last of the `judged` moving poses the verdict `seen` was drawn from."""
    moving = [t for t, pose in zip(exercise.pose_times('turtle1'), poses.messages()) if pose.linear_velocity > 0]
    if not moving:
        return
    exercise.mark(moving[0], 'turtle1 drives: the circle is judged from here', 'circle')
    if len(moving) >= full_turn:
        exercise.mark(moving[full_turn - 1], 'a full turn driven: the circle closes', 'circle')
    exercise.mark(moving[max(0, min(judged, len(moving)) - 1)], 'the circle judged: %s' % seen, 'circle')


def check_spawn_kill(session):
    criterion = session.rubric.criterion('spawn_kill')
    spawn = tuple(criterion['spawn'])
    # turtlesim's window at the end is the picture; its lines are the grader's (the trusted side's).
    exercise = Exercise(session, criterion, 'exercise4.log', picture='spawn_kill.png')
    poses = exercise.poses('robotics')
    try:
        if not exercise.wait(lambda: poses.count(), session.rubric.limits['start_seconds']):
            spawned = Verdict(False, exercise.nothing('spawn the turtle robotics'))
        else:
            at_start = turtle.at_pose(poses.latest(), spawn, criterion['tolerance'])
            gone = exercise.wait(lambda: exercise.turtles() is not None and 'turtle1' not in exercise.turtles(), 5)
            spawned = Verdict(at_start.passed and gone, 'expected robotics at (%.2f, %.2f, %.2f) and turtle1 killed; '
                              'seen robotics %s, turtle1 %s' % (spawn + (at_start.reason, 'killed' if gone else
                                                                         'still there')))
        cleared = exercise.wait(lambda: any(re.search(r'Clearing turtlesim\.\s*$', line)
                                            for line in exercise.simulator_lines), 5)
        return exercise.judged({'spawn_kill': exercise.on_interface(poses, 'robotics') or spawned,
                                'clear': Verdict(cleared, 'expected `%s` to clear the background with /clear; seen %s' % (
                                    exercise.command, 'turtlesim print `Clearing turtlesim.`' if cleared else
                                    'no line `Clearing turtlesim.` from turtlesim: call its service /clear '
                                    '(std_srvs/Empty)'))})
    finally:
        exercise.finish()


def check_shape(session, shape):
    criterion = session.rubric.criterion(shape)
    side, tolerance = criterion['side'], criterion['tolerance']
    start = tuple(criterion['spawn'])
    outline = figures.polygon(*start, side, {'square': 4, 'triangle': 3}[shape])
    # The closed loop ends each side and turn from the pose: turtlesim waits for its answer to each
    # pose (lock step), so a machine that keeps the student's node waiting does not move the turtle on.
    exercise = Exercise(session, criterion, 'exercise5_%s.log' % shape, *_args(session, shape),
                        picture='%s.png' % shape, lock_step=True)
    poses = exercise.poses('robotics')
    try:
        finished = exercise.wait(lambda: exercise.printed(r'(Finished) the %s' % shape))
        path = turtle.pose_array(poses)
        if not len(path):
            return exercise.judged({shape: Verdict(False, exercise.nothing('spawn robotics and drive a %s' % shape))})
        closed = figures.closed_path(path[:, :2], outline, tolerance)
        verdict = Verdict(finished and closed.passed, 'expected a %s of side %g m from (%g, %g) back to its start, '
                          'within %g m; seen %s%s' % (shape, side, start[0], start[1], tolerance, closed.reason,
                                                      '' if finished else ', and no line `Finished the %s`' % shape))
        return exercise.judged({shape: exercise.on_interface(poses, 'robotics') or verdict})
    finally:
        exercise.finish()


def read_launches(session):
    """Each launch file the lab runs, read at once: one run of roslaunch's loader for them all."""
    describe_launches(session, _launches(session))
    return {}


# Decided without a run: builds by the session's build.
STATIC_CRITERIA = {
    'builds': (),
}
# The lab's steps after the build, in order: the six launch files read, then each run.
RUNS = (
    LabRun('exercise1-5.launch', read_launches, {}, (READING,)),
    LabRun('exercise1.launch', check_publisher, {
        'publisher_rate': ('launch_file', 'rate', 'id_number', 'skipped', 'messages', 'tolerance',
                           'real_time_factor'),
    }, (NODES,)),
    LabRun('exercise1.launch:subscriber', check_subscriber, {
        'subscriber_prints': ('launch_file', 'executable', 'digits'),
    }, (NODES,), log='exercise1_subscriber.log'),
    LabRun('exercise2.launch', check_listener, {
        'listener_prints_pose': ('launch_file', 'linear', 'angular', 'until_x', 'real_time_factor'),
    }, (NODES,)),
    LabRun('exercise3.launch', check_circle, {
        'circle': ('launch_file', 'start', 'radius', 'tolerance', 'turn_seconds', 'real_time_factor'),
    }, (NODES,)),
    LabRun('exercise4.launch', check_spawn_kill, {
        'spawn_kill': ('launch_file', 'spawn', 'tolerance', 'real_time_factor'),
        'clear': (),
    }, (NODES,)),
    LabRun('exercise5_square.launch', functools.partial(check_shape, shape='square'), {
        'square': ('launch_file', 'spawn', 'side', 'speed', 'turn_speed', 'tolerance', 'real_time_factor'),
    }, (NODES,)),
    LabRun('exercise5_triangle.launch', functools.partial(check_shape, shape='triangle'), {
        'triangle': ('launch_file', 'spawn', 'side', 'speed', 'turn_speed', 'tolerance', 'real_time_factor'),
    }, (NODES,)),
)
CRITERIA = criteria_of(STATIC_CRITERIA, RUNS)
# The settings that are [low, high] bounds of a number drawn at each grading (rubric.check_drawn).
DRAWN = (('listener_prints_pose', 'linear'), ('listener_prints_pose', 'angular'))


def run_checks(session):
    return run_each(session, RUNS)


def static_checks(session):
    return {}
