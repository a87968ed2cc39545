"""The turtlesim lab (seed 000): my_turtle's move_turtle.launch, the teleop relay and the pose
printout, on the course's turtlesim, with the helpers of my_turtle's own tests (my_turtle_testing)."""
import re
import threading
import time

import rospy
from geometry_msgs.msg import Twist

from course_grader.labs.common import BoundedLaunch, node_names, run_each
from course_grader.results import Outcome
from course_grader.session import Deadline, test_helpers
from course_testing.waiting import wait_until

test_helpers('my_turtle')
import my_turtle_testing  # noqa: E402  (my_turtle's test helpers: turtle1_poses, travelled, turned)

PRINTED_POSE = re.compile(r'x: (-?\d+\.\d+), y: (-?\d+\.\d+)')


def _wait(condition, seconds):
    try:
        return wait_until(condition, seconds, poll=0.05)
    except AssertionError:
        return False


def check_turtle(session):
    rubric = session.rubric
    launch_c, teleop_c, pose_c = (rubric.criterion(i) for i in ('launch', 'teleop', 'prints_pose'))
    deadline = Deadline(rubric.limits['run_seconds'])
    picture = session.log_path('turtle.png')
    rospy.set_param('/turtlesim_node/canvas_png', picture)
    session.pictures.append('turtle.png')
    known = node_names()
    launch_file = launch_c.get('launch_file', 'move_turtle.launch')
    runs = [BoundedLaunch(['roslaunch', rubric.package, launch_file], session.log_path('move_turtle.log'))]
    outcomes = {}
    try:
        def started():
            return {'/turtlesim_node', '/my_turtle_node'} <= node_names() - known
        launched = _wait(lambda: started() or runs[0].process.poll() is not None,
                         rubric.limits['start_seconds']) and started()
        seen = sorted(node_names() - known)
        if launched:
            outcomes['launch'] = Outcome(True, 'started %s' % ', '.join(seen))
        else:
            tail = [line for line in runs[0].lines if 'ERROR' in line or 'rror' in line][:2]
            outcomes['launch'] = Outcome(False, 'expected `roslaunch %s %s` to start /turtlesim_node and '
                                         '/my_turtle_node; seen: %s%s' % (
                                             rubric.package, launch_file, ', '.join(seen) or 'no node',
                                             ('; ' + ' | '.join(tail)) if tail else ''))
            # The other criteria still get their chance: turtlesim and the node, started by hand.
            runs[0].stop_in(rubric.limits['stop_seconds'])
            if '/turtlesim_node' not in node_names():
                runs.append(BoundedLaunch(['rosrun', 'turtlesim', 'turtlesim_node', '__name:=turtlesim_node'],
                                          session.log_path('turtlesim.txt')))
            runs.append(BoundedLaunch(['rosrun', rubric.package, launch_c.get('executable', 'my_turtle_node'),
                                       '__name:=my_turtle_node'], session.log_path('my_turtle_node.log')))
            if not _wait(lambda: '/my_turtle_node' in node_names(), rubric.limits['start_seconds']):
                reason = 'not checked: the node %s did not start' % launch_c.get('executable', 'my_turtle_node')
                return dict(outcomes, teleop=Outcome(False, reason), prints_pose=Outcome(False, reason))
        watch = my_turtle_testing.turtle1_poses()
        teleop = rospy.Publisher('/cmd_vel_mux/input/teleop', Twist, queue_size=1)
        _wait(lambda: teleop.get_num_connections() > 0, 10)
        command = Twist()
        command.linear.x, command.angular.z = teleop_c.get('linear', 1.0), teleop_c.get('angular', 0.5)
        holding = threading.Event()
        holding.set()

        def hold():   # 10 Hz, as the keyboard teleop sends a held key
            while holding.is_set():
                teleop.publish(command)
                time.sleep(0.1)
        sender = threading.Thread(target=hold, daemon=True)
        sender.start()
        _wait(lambda: my_turtle_testing.travelled(watch.entries()[-10:]) > 0.01, min(10, deadline.left()))
        samples = watch.record(teleop_c.get('seconds', 2.0))
        holding.clear()
        sender.join()
        teleop.publish(Twist())
        speed = my_turtle_testing.travelled(samples) / my_turtle_testing.duration(samples)
        rate = my_turtle_testing.turned(samples) / my_turtle_testing.duration(samples)
        tolerance = teleop_c.get('tolerance', 0.1)
        ok = (abs(speed - command.linear.x) <= tolerance * abs(command.linear.x)
              and abs(rate - command.angular.z) <= tolerance * abs(command.angular.z))
        outcomes['teleop'] = Outcome(ok, 'expected the turtle at %.2f m/s turning %.2f rad/s while that Twist comes '
                                     'on cmd_vel_mux/input/teleop; seen %.2f m/s turning %.2f rad/s' % (
                                         command.linear.x, command.angular.z, speed, rate))
        # The printout: after the turtle stopped, the last pose printed is the pose turtlesim publishes.
        _wait(lambda: my_turtle_testing.travelled(watch.record(0.3)) < 1e-3, min(10, deadline.left()))
        final = watch.latest()
        node_run = runs[-1]

        def printed():
            found = [PRINTED_POSE.search(line) for line in node_run.lines[-20:]]
            return [(float(m.group(1)), float(m.group(2))) for m in found if m]
        tolerance = pose_c.get('tolerance', 0.011)
        matched = _wait(lambda: any(abs(x - final.x) <= tolerance and abs(y - final.y) <= tolerance
                                    for x, y in printed()), 5)
        last = printed()[-1:] or None
        outcomes['prints_pose'] = Outcome(matched, 'expected lines `x: %.2f, y: %.2f` (the pose turtlesim '
                                          'publishes, printed on every pose); seen %s' % (
                                              final.x, final.y, 'last printed x: %.2f, y: %.2f' % last[0] if last
                                              else 'no line `x: ..., y: ...` printed'))
        return outcomes
    finally:
        for run in reversed(runs):
            run.stop_in(rubric.limits['stop_seconds'])


def run_checks(session):
    return run_each(session, [(check_turtle, 'move_turtle.launch', ['launch', 'teleop', 'prints_pose'])])


def static_checks(session):
    return {}

