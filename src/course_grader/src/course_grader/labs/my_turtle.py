"""The turtlesim lab (seed 000): my_turtle's move_turtle.launch, the teleop relay and the pose
printout, on the course's turtlesim (started by the grader in place of the launch file's own,
labs.turtlesim_runs), with the checks of course_checks that my_turtle's own tests use."""
import re
import threading
import time

import rospy
from geometry_msgs.msg import Twist

from course_checks import turtle
from course_checks.robot import node_names
from course_checks.verdict import Verdict
from course_common.waiting import Deadline, wait_for
from course_grader.labs.common import LabRun, criteria_of, drawn, run_each
from course_grader.labs.turtlesim_runs import TurtlesimLaunch
from course_grader.wall_limit import NODES, READING

PRINTED_POSE = re.compile(r'x: (-?\d+\.\d+), y: (-?\d+\.\d+)')
SIMULATOR = '/turtlesim_node'


def check_turtle(session):
    rubric = session.rubric
    launch_c, teleop_c, pose_c = (rubric.criterion(i) for i in ('launch', 'teleop', 'prints_pose'))
    deadline = Deadline(rubric.limits['run_seconds'])
    known = node_names()
    launch_file = launch_c['launch_file']
    # turtlesim in real time; the teleop criterion measures the turtle's speed in its own ticks.
    launch = TurtlesimLaunch(session, launch_file, [], 'move_turtle.log', picture='turtle.png')
    runs = [launch.run]
    outcomes = {}
    try:
        def started():
            return '/my_turtle_node' in node_names() - known
        launched = SIMULATOR in launch.simulators and wait_for(started, rubric.limits['start_seconds'],
                                                                gave_up=launch.run.ended)
        seen = sorted(set(launch.simulators) | (node_names() - known))
        if launched:
            outcomes['launch'] = Verdict(True, 'started %s' % ', '.join(seen))
        else:
            outcomes['launch'] = Verdict(False, 'expected `roslaunch %s %s` to start %s (turtlesim) and '
                                         '/my_turtle_node; seen: %s%s' % (
                                             rubric.package, launch_file, SIMULATOR, ', '.join(seen) or 'no node',
                                             '; ' + (launch.unread or launch.run.error_lines())))
            # The other criteria still get their chance: turtlesim and the node, started by hand.
            launch.run.stop(rubric.limits['stop_seconds'])
            if not launch.simulators:   # one the launch file declared under another name stays
                launch.start_turtlesim({'name': SIMULATOR, 'remaps': [], 'params': {}}, picture='turtle.png')
            runs.append(session.student(['rosrun', rubric.package, launch_c['executable'],
                                         '__name:=my_turtle_node'], 'my_turtle_node.log'))
            if not wait_for(lambda: '/my_turtle_node' in node_names(), rubric.limits['start_seconds']):
                reason = 'not checked: the node %s did not start' % launch_c['executable']
                return launch.judged(dict(outcomes, teleop=Verdict(False, reason), prints_pose=Verdict(False, reason)))
        watch = launch.poses('turtle1')
        teleop = rospy.Publisher('/cmd_vel_mux/input/teleop', Twist, queue_size=1)
        wait_for(lambda: teleop.get_num_connections() > 0, 10)
        # A Twist drawn for this grading: a node that publishes a known one on turtle1/cmd_vel, hearing
        # nothing, does not pass for one that passes the teleop's on.
        command = Twist()
        command.linear.x, command.angular.z = drawn(teleop_c['linear']), drawn(teleop_c['angular'], either_way=True)
        holding = threading.Event()
        holding.set()

        def hold():   # 10 Hz, as the keyboard teleop sends a held key
            while holding.is_set():
                teleop.publish(command)
                time.sleep(0.1)
        sender = threading.Thread(target=hold, daemon=True)
        sender.start()
        deadline.wait(lambda: turtle.moving(watch), 10)
        first = watch.count()
        samples = watch.record(teleop_c['seconds'])
        holding.clear()
        sender.join()
        teleop.publish(Twist())
        followed = turtle.drives_at(samples, command.linear.x, command.angular.z, teleop_c['tolerance'])
        outcomes['teleop'] = Verdict(followed.passed, 'expected the turtle at %.2f m/s turning %.2f rad/s while that '
                                     'Twist comes on cmd_vel_mux/input/teleop; seen %s' % (
                                         command.linear.x, command.angular.z, followed.reason))
        window = launch.pose_times('turtle1')[first:first + len(samples)]
        if window:
            launch.mark(window[0], 'the teleop window opens: %.2f m/s turning %.2f rad/s sent on '
                        'cmd_vel_mux/input/teleop' % (command.linear.x, command.angular.z), 'teleop')
            launch.mark(window[-1], 'the teleop window judged: %s' % followed.reason, 'teleop')
        # The printout: after the turtle stopped, the last pose printed is the pose turtlesim publishes.
        deadline.wait(lambda: turtle.standing(watch), 10)
        final = watch.latest()
        node_run = runs[-1]

        def printed():
            found = [PRINTED_POSE.search(line) for line in node_run.lines[-20:]]
            return turtle.printed_position([(float(m.group(1)), float(m.group(2))) for m in found if m], final,
                                           pose_c['tolerance'])
        wait_for(lambda: printed().passed, 5)
        shown = printed()
        outcomes['prints_pose'] = Verdict(shown.passed, 'expected lines `x: %.2f, y: %.2f` (the pose turtlesim '
                                          'publishes, printed on every pose); seen %s' % (final.x, final.y, shown.reason))
        # A node that published on turtle1/pose fails both (launch.judged).
        outcomes['teleop'] = (turtle.no_unused_calls(launch.service_calls()) or turtle.no_jumps(watch, 'turtle1')
                              or outcomes['teleop'])
        judged = launch.judged({criterion_id: outcomes[criterion_id] for criterion_id in ('teleop', 'prints_pose')})
        return dict(outcomes, **judged)
    finally:
        for run in reversed(runs[1:]):
            run.stop(rubric.limits['stop_seconds'])
        launch.finish()


# Decided without a run: builds by the session's build.
STATIC_CRITERIA = {
    'builds': (),
}
# The lab's run after the build: move_turtle.launch read (TurtlesimLaunch), then run; when it does
# not start the node, the node by rosrun.
RUNS = (
    LabRun('move_turtle.launch', check_turtle, {
        'launch': ('launch_file', 'executable'),
        'teleop': ('linear', 'angular', 'seconds', 'tolerance'),
        'prints_pose': ('tolerance',),
    }, (READING, NODES, NODES)),
)
CRITERIA = criteria_of(STATIC_CRITERIA, RUNS)
# The settings that are [low, high] bounds of a number drawn at each grading (rubric.check_drawn).
DRAWN = (('teleop', 'linear'), ('teleop', 'angular'))


def run_checks(session):
    return run_each(session, RUNS)


def static_checks(session):
    return {}

