"""The lab report's exercises (seed 002): ros_exercises' launch files exercise1..5 on the course's
turtlesim, with the checks of ros_exercises' own tests (ros_exercises_testing, figures,
test_publisher_subscriber, test_listener_circle)."""
import math
import re
import time
import unittest

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Int32

from course_grader.labs.common import BoundedLaunch, run_each
from course_grader.results import Outcome
from course_grader.session import Deadline, test_helpers
from course_testing.recording import TopicRecorder
from course_testing.waiting import wait_until

test_helpers('ros_exercises')
import figures                     # noqa: E402  (ros_exercises' test helpers: polygon, distances_to_polygon)
import printed_poses               # noqa: E402  (summary of the printed poses' judgement)
import ros_exercises_testing       # noqa: E402  (turtle_poses, pose_array)
import test_listener_circle        # noqa: E402  (assert_printed_poses_were_published, assert_circle)
import test_publisher_subscriber   # noqa: E402  (rate_of, assert_cycles_through)

NUMBER = test_listener_circle.NUMBER
COLOUR = re.compile(r'\x1b\[[0-9;]*m')
SPAWN_START = (1.0, 1.0, 0.0)      # where exercise4.launch (and so exercise5.launch) spawns robotics


def _wait(condition, seconds):
    try:
        return wait_until(condition, seconds, poll=0.05)
    except AssertionError:
        return False


def _failure(check, *args):
    """Runs one of the tests' assert_* checks: None when it holds, else its message."""
    try:
        check(unittest.TestCase(), *args)
    except AssertionError as error:
        return str(error).strip() or 'the check failed'
    return None


def _printed(run, pattern):
    return [match.groups() for match in (re.search(pattern, line) for line in run.lines) if match]


def _printed_poses(printed, poses):
    """The course test's check that the printed poses are those turtlesim published: (what is
    wrong or None, a summary of what was printed)."""
    try:
        judgement = test_listener_circle.assert_printed_poses_were_published(unittest.TestCase(), printed, poses)
    except AssertionError as error:
        return str(error), None
    return None, printed_poses.summary(judgement)


def _tail(run, count=2):
    """The first error lines of a launch, as a hint of why nothing came of it."""
    lines = [COLOUR.sub('', line).strip() for line in run.lines]   # roslaunch prints its errors in red
    errors = [line for line in lines if 'ERROR' in line or 'rror' in line or 'Exception' in line or 'not found' in line]
    return (' | '.join(errors[:count])) or 'no error printed'


class Exercise:
    """One of the student's launch files (with its own turtlesim), logged to <name>.log, stopped at the end."""

    def __init__(self, session, criterion, log_name, *args, picture=None):
        self.session = session
        self.deadline = Deadline(session.rubric.limits['run_seconds'])
        if picture:   # turtlesim saves its canvas there when it stops
            rospy.set_param('/turtlesim/canvas_png', session.log_path(picture))
            session.pictures.append(picture)
        else:
            rospy.set_param('/turtlesim/canvas_png', '')
        self.command = 'roslaunch %s %s%s' % (session.rubric.package, criterion.get('launch_file'),
                                              ''.join(' ' + arg for arg in args))
        self.run = BoundedLaunch(['roslaunch', session.rubric.package, criterion.get('launch_file')] + list(args),
                                 session.log_path(log_name))

    def wait(self, condition, seconds=None):
        """condition() within `seconds` (the run's time left at most); False as soon as the launch ended."""
        limit = self.deadline.left() if seconds is None else min(seconds, self.deadline.left())
        return _wait(lambda: condition() or self.run.process.poll() is not None, limit) and bool(condition())

    def printed(self, pattern):
        return _printed(self.run, pattern)

    def nothing(self, what):
        return 'expected `%s` to %s; seen: %s' % (self.command, what, _tail(self.run))

    def stop(self):
        self.run.stop_in(self.session.rubric.limits['stop_seconds'])


def check_publisher_subscriber(session):
    rate_c = session.rubric.criterion('publisher_rate')
    id_number, rate = str(rate_c.get('id_number', '4095127')), rate_c.get('rate', 50)
    count = int(rate_c.get('messages', 100)) + 10
    digits = TopicRecorder('/ZabirovaKostyukova', Int32)
    exercise = Exercise(session, rate_c, 'exercise1.log', 'rate:=%g' % rate, 'id:=' + id_number)
    window = 1.5 * count / rate   # seconds from the first digit: a slower publisher is measured over what came

    def measured_enough():
        entries = digits.entries()
        return len(entries) >= count or bool(entries and time.monotonic() - entries[0][0] > window)
    outcomes = {}
    try:
        exercise.wait(measured_enough, session.rubric.limits['start_seconds'] + window)
        if digits.count() < 12:
            outcomes['publisher_rate'] = Outcome(False, exercise.nothing(
                'publish the digits of %s on /ZabirovaKostyukova; %d arrived' % (id_number, digits.count())))
        else:
            measured = test_publisher_subscriber.rate_of(digits.entries()[10:count])
            wrong_digits = _failure(test_publisher_subscriber.assert_cycles_through,
                                    [digit.data for digit in digits.messages()], id_number)
            ok = abs(measured - rate) <= rate_c.get('tolerance', 1.0) and not wrong_digits
            outcomes['publisher_rate'] = Outcome(ok, 'expected the digits of %s, in order, at %g Hz ± %g; seen '
                                                 '%.2f Hz%s' % (id_number, rate, rate_c.get('tolerance', 1.0), measured,
                                                                '; ' + wrong_digits if wrong_digits else ''))
        heard_pattern = r'I heard: \[(\d+)\]'
        wanted = 3 * len(id_number)
        exercise.wait(lambda: len(exercise.printed(heard_pattern)) >= wanted, 10)
        heard = [int(digit) for (digit,) in exercise.printed(heard_pattern)]
        if len(heard) < wanted:
            outcomes['subscriber_prints'] = Outcome(False, 'expected the subscriber to print `I heard: [d]` for '
                                                    'each digit of %s; seen %d such lines' % (id_number, len(heard)))
        else:
            wrong = _failure(test_publisher_subscriber.assert_cycles_through, heard, id_number)
            outcomes['subscriber_prints'] = Outcome(not wrong, 'expected `I heard: [d]` for each digit of %s, in '
                                                    'order; seen %s' % (id_number, wrong or 'them'))
        return outcomes
    finally:
        exercise.stop()
        digits.close()


def check_listener(session):
    criterion = session.rubric.criterion('listener_prints_pose')
    poses = ros_exercises_testing.turtle_poses('turtle1')
    exercise = Exercise(session, criterion, 'exercise2.log')
    line = r'x: %s, y: %s, theta: %s' % (NUMBER, NUMBER, NUMBER)
    teleop = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
    timer = None
    try:
        if not exercise.wait(lambda: exercise.printed(line), session.rubric.limits['start_seconds']):
            return {'listener_prints_pose': Outcome(False, exercise.nothing('print lines `x: .., y: .., theta: ..`'))}
        # The grader hears every pose from here on: the turtle stands still until then.
        exercise.wait(lambda: poses.count(), 10)
        # Drive the turtle as a teleop would, until the listener has printed it moving.
        command = Twist()
        command.linear.x, command.angular.z = 1.0, 0.5
        timer = rospy.Timer(rospy.Duration(0.05), lambda _: teleop.publish(command))
        moved = exercise.wait(lambda: any(float(x) > 6.0 for x, _, _ in exercise.printed(line)), 10)
        timer.shutdown()
        printed = exercise.printed(line)
        wrong, seen = _printed_poses(printed, poses)
        if not moved:
            wrong = 'the printed pose did not follow the turtle driven to x > 6 (last printed %s)' % (printed[-1],)
        seen = wrong or seen
        return {'listener_prints_pose': Outcome(not wrong, 'expected the pose turtlesim publishes, printed as '
                                                'the turtle moves; seen %s' % seen)}
    finally:
        if timer:
            timer.shutdown()
        teleop.unregister()
        exercise.stop()
        poses.close()


def check_circle(session):
    criterion = session.rubric.criterion('circle')
    poses = ros_exercises_testing.turtle_poses('turtle1')
    exercise = Exercise(session, criterion, 'exercise3.log', picture='circle.png')
    try:
        if not exercise.wait(lambda: poses.count() and poses.latest().linear_velocity > 0,
                             session.rubric.limits['start_seconds']):
            return {'circle': Outcome(False, exercise.nothing('drive turtle1'))}
        # turtle1 starts at the middle facing +x: the centre is 1 m to its left.
        centre = (test_listener_circle.TURTLE1_START[0], test_listener_circle.TURTLE1_START[1] + 1.0)
        wrong, seen = _failure(test_listener_circle.assert_circle, poses, centre, 1.0), None
        if not wrong:
            printed = exercise.printed(r'Turtle subscriber@\[%s, %s, %s\]' % (NUMBER, NUMBER, NUMBER))
            wrong, seen = (_printed_poses(printed, poses) if printed
                           else ('no line `Turtle subscriber@[x, y, theta]` printed', None))
        return {'circle': Outcome(not wrong, 'expected a circle of radius 1 m around (%.2f, %.2f), with the pose '
                                  'printed; seen %s' % (centre[0], centre[1], wrong or 'it: ' + seen))}
    finally:
        exercise.stop()
        poses.close()


def _turtles():
    return {topic.split('/')[1] for topic, _ in rospy.get_published_topics() if topic.endswith('/pose')}


def check_spawn_kill(session):
    criterion = session.rubric.criterion('spawn_kill')
    poses = ros_exercises_testing.turtle_poses('robotics')
    # --screen: turtlesim's own log lines come with the launch's output, as in the terminal of
    # `rosrun turtlesim turtlesim_node`; its window at the end is the picture.
    exercise = Exercise(session, criterion, 'exercise4.log', '--screen', picture='spawn_kill.png')
    try:
        if not exercise.wait(lambda: poses.count(), session.rubric.limits['start_seconds']):
            spawned = Outcome(False, exercise.nothing('spawn the turtle robotics'))
        else:
            pose = poses.latest()
            gone = exercise.wait(lambda: 'turtle1' not in _turtles(), 5)
            at_start = max(abs(a - b) for a, b in zip((pose.x, pose.y, pose.theta), SPAWN_START)) <= 1e-5
            spawned = Outcome(at_start and gone, 'expected robotics at (1.00, 1.00, 0.00) and turtle1 killed; seen '
                              'robotics at (%.2f, %.2f, %.2f), turtle1 %s' % (
                                  pose.x, pose.y, pose.theta, 'killed' if gone else 'still there'))
        cleared = exercise.wait(lambda: exercise.printed(r'(Clearing turtlesim\.)\s*$'), 5)
        return {'spawn_kill': spawned,
                'clear': Outcome(cleared, 'expected `%s` to clear the background with /clear; seen %s' % (
                    exercise.command, 'turtlesim print `Clearing turtlesim.`' if cleared else
                    'no line `Clearing turtlesim.` from turtlesim: call its service /clear (std_srvs/Empty)'))}
    finally:
        exercise.stop()
        poses.close()


def check_shape(session, shape):
    criterion = session.rubric.criterion(shape)
    side, tolerance = criterion.get('side', 2.0), criterion.get('tolerance', 0.05)
    outline = figures.polygon(*SPAWN_START, side, {'square': 4, 'triangle': 3}[shape])
    poses = ros_exercises_testing.turtle_poses('robotics')
    exercise = Exercise(session, criterion, 'exercise5_%s.log' % shape, 'shape:=' + shape, 'side:=%g' % side,
                        'speed:=%g' % criterion.get('speed', 2.0), 'turn_speed:=%g' % criterion.get('turn_speed', 2.0),
                        picture='%s.png' % shape)
    try:
        finished = exercise.wait(lambda: exercise.printed(r'(Finished) the %s' % shape))
        path = ros_exercises_testing.pose_array(poses)
        if not len(path):
            return {shape: Outcome(False, exercise.nothing('spawn robotics and drive a %s' % shape))}
        away = figures.distances_to_polygon(path[:, :2], outline).max()
        end = path[-1]
        missed = math.hypot(end[0] - SPAWN_START[0], end[1] - SPAWN_START[1])
        ok = finished and away <= tolerance and missed <= tolerance
        return {shape: Outcome(ok, 'expected a %s of side %g m from (1, 1) back to its start, within %g m; seen '
                               'the path at most %.3f m off the outline, ending %.3f m from the start%s' % (
                                   shape, side, tolerance, away, missed,
                                   '' if finished else ', and no line `Finished the %s`' % shape))}
    finally:
        exercise.stop()
        poses.close()


def run_checks(session):
    return run_each(session, [
        (check_publisher_subscriber, 'exercise1.launch', ['publisher_rate', 'subscriber_prints']),
        (check_listener, 'exercise2.launch', ['listener_prints_pose']),
        (check_circle, 'exercise3.launch', ['circle']),
        (check_spawn_kill, 'exercise4.launch', ['spawn_kill', 'clear']),
        (lambda s: check_shape(s, 'square'), 'exercise5_square.launch', ['square']),
        (lambda s: check_shape(s, 'triangle'), 'exercise5_triangle.launch', ['triangle'])])


def static_checks(session):
    return {}
