"""The labs of the tour: each starts what the course starts, measures what a student would look at,
and returns a few summary lines and the pictures it saved."""
import collections
import math
import re
import time

import rospy
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import UInt32
from turtlesim.msg import Pose

from course_checks import driving
from course_testing.processes import PtyProgram
from course_checks.figures import path_length
from course_common.topic_recorder import TopicRecorder
from course_testing.rviz import rviz_until_drawn
from course_testing.screen import VirtualScreen, can_make_screens, red_pixels
from course_common.waiting import wait_until

LabReport = collections.namedtuple('LabReport', 'lines pictures')
Lab = collections.namedtuple('Lab', 'name title run')


def _turtle_poses(name):
    return TopicRecorder('/%s/pose' % name, Pose)


def _points(recorder):
    return [(pose.x, pose.y) for pose in recorder.messages()]


def _save_canvas(session, simulator_node, file_name):
    """Ask a running turtlesim (named simulator_node by its launch file) to write its canvas."""
    path = session.picture(file_name)
    rospy.set_param('/%s/canvas_png' % simulator_node, path)
    return session.call_trigger('/%s/save_canvas' % simulator_node)


# The labs whose nodes answer each pose run on turtlesim's simulated clock, this many times as fast
# as real time, each tick waiting for the node's answer (turtlesim's ~lock_step, as the grader runs
# the shapes): the turtle drives the same path, and draws the same picture, at any factor and load.
TURTLESIM_FACTOR = 5


def _turtlesim_clock(simulator_node):
    """The parameters that put the turtlesim node of that name, and the nodes, on its simulated clock."""
    return {'/use_sim_time': True, '/%s/real_time_factor' % simulator_node: TURTLESIM_FACTOR,
            '/%s/lock_step' % simulator_node: True}


def turtlesim_square(session):
    """turtlesim's draw_square drives turtle1 once round its 2 m square; the canvas is saved."""
    canvas = session.picture('turtlesim-square.png')
    poses, clock = _turtle_poses('turtle1'), TopicRecorder('/clock', Clock)
    launched = session.launch('turtlesim', 'draw_square_demo.launch', params=_turtlesim_clock('turtlesim'),
                              canvas_png=canvas)
    # Four sides and four turns: draw_square logs "Reached goal" after each.
    wait_until(lambda: launched.output().count('Reached goal') >= 8, 90,
               'draw_square to reach the 8 goals of one square')
    seconds = clock.latest().clock.to_sec()   # turtlesim's clock starts at 0
    clock.close()
    points = _points(poses)
    poses.close()
    session.stop(launched)  # the simulator writes the canvas as it shuts down
    gap = math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1])
    return LabReport(['turtle1 drove %.2f m round the square in %.0f simulated seconds and ended %.2f m from its start'
                      % (path_length(points), seconds, gap)], [canvas])


def my_turtle_pose(session):
    """000, stage 2: my_turtle_pose drives forward at 0.5 m/s and prints every pose."""
    poses = _turtle_poses('turtle1')
    launched = session.launch('my_turtle', 'move_pose.launch')
    wait_until(lambda: path_length(_points(poses)) > 2.0, 30, 'turtle1 to drive 2 m')
    points = _points(poses)
    first, last = poses.messages()[0], poses.messages()[-1]
    poses.close()
    canvas = _save_canvas(session, 'turtlesim_node', 'my_turtle-forward.png')
    session.stop(launched)
    printed = re.findall(r'x: \d+\.\d\d, y: \d+\.\d\d', launched.output())
    return LabReport([
        'turtle1 drove %.2f m along +x, from x=%.2f to x=%.2f (y stayed %.2f)'
        % (path_length(points), first.x, last.x, last.y),
        'my_turtle_pose printed %d pose lines, the last: "%s"' % (len(printed), printed[-1]),
    ], [canvas])


# Keys typed into the teleop: speed up (w), forward (i), left (j), stop (k), as a student would.
# The teleop stops smoothly after 4 passes (0.4 s) without a key, so keys repeat every 0.2 s.
TELEOP_SCRIPT = [('w', 8), ('i', 15), ('j', 8), ('i', 15), ('j', 8), ('i', 15), ('k', 2)]


def my_turtle_teleop(session):
    """000, stage 3: the keyboard teleop drives turtle1 through my_turtle_node's relay."""
    poses = _turtle_poses('turtle1')
    chain = PtyProgram(['roslaunch', '--wait', 'my_turtle', 'teleop_chain.launch'], env=session.env)
    try:
        chain.wait_for_output('currently:', 60)
        wait_until(lambda: poses.messages(), 30, 'the pose of turtle1')
        for key, repeats in TELEOP_SCRIPT:
            for _ in range(repeats):
                chain.type(key)
                time.sleep(0.2)  # typing speed of the script, not a wait for a result
        wait_until(lambda: poses.messages()[-1].linear_velocity == 0.0, 10,
                   'turtle1 to stop after k')
        canvas = _save_canvas(session, 'turtlesim_node', 'my_turtle-teleop.png')
        speeds = re.findall(r'currently:\s+speed ([\d.]+)\s+turn ([\d.]+)', chain.read_available())
    finally:
        chain.stop()
    points = _points(poses)
    poses.close()
    return LabReport([
        'typed %d keys; the teleop ended at speed %s m/s, turn %s rad/s'
        % (sum(n for _, n in TELEOP_SCRIPT), speeds[-1][0], speeds[-1][1]),
        'turtle1 followed the relay for %.2f m and stopped on k' % path_length(points),
    ], [canvas])


def report_shapes(session):
    """002, exercise 5: the spawned turtle `robotics` drives a square, then a triangle."""
    lines, pictures = [], []
    for shape in ('square', 'triangle'):
        poses = _turtle_poses('robotics')
        launched = session.launch('ros_exercises', 'exercise5.launch', params=_turtlesim_clock('turtlesim'),
                                  shape=shape)
        finished = wait_until(
            lambda: re.search(r'Finished the %s at .*, ([\d.]+) m from the start' % shape,
                              launched.output()), 120, 'the %s to be finished' % shape)
        points = _points(poses)
        poses.close()
        # Saved while the turtle is still on the canvas: the picture shows it at the end of its figure.
        pictures.append(_save_canvas(session, 'turtlesim', 'ros_exercises-%s.png' % shape))
        session.stop(launched)
        lines.append('%s of 3 m sides: %.2f m driven, closed within %.3f m'
                     % (shape, path_length(points), float(finished.group(1))))
    return LabReport(lines, pictures)


def _odom_points(recorder):
    return [(odom.pose.pose.position.x, odom.pose.pose.position.y) for odom in recorder.messages()]


def _collisions(recorder):
    counts = recorder.messages()
    return counts[-1].data if counts else 0


LASER_BLOCK = re.compile(r's1 \[0\]\s+(\S+)\s+s2 \[90\]\s+(\S+)\s+s3 \[180\]\s+(\S+)\s+'
                         r's4 \[270\]\s+(\S+)\s+s5 \[359\]\s+(\S+)')


def turtlebot3_laser(session):
    """001: laser_data.py prints beams 0, 90, 180, 270 and 359 of fake_tb3's scans."""
    launched = session.launch('move_turtlebot3', 'laser_data.launch')
    wait_until(lambda: len(LASER_BLOCK.findall(launched.output())) >= 3, 60,
               'laser_data to print three scans')
    session.stop(launched)
    blocks = LASER_BLOCK.findall(launched.output())
    last = ['%.3f m' % float(value) if value != 'inf' else 'inf' for value in blocks[-1]]
    return LabReport(['laser_data printed %d scans; the last: front %s, left %s, back %s, right %s, '
                      '359: %s (inf: nothing within 3.5 m)' % tuple([len(blocks)] + last)], [])


# Simulated seconds the robot stands still before the tour reads the front beam: the median of
# these 10 scans, as the grader judges the stop (course_checks.driving), not one noisy reading.
STOP_WATCH_S = 2.0
# Both nodes answer each scan: fake_tb3 runs them this many times as fast as real time, in lock step
# with them (its ~lock_step, as the grader runs avoid_obstacle.py), so they meet the same simulated
# delays at any factor and load.
AVOID_FACTOR, WANDER_FACTOR = 10, 20
LOCK_STEP = {'/fake_tb3/lock_step': True}


def turtlebot3_avoid(session):
    """001: avoid_obstacle.py drives at the wall and stops; wander.py roams 120 simulated seconds."""
    scans, odoms = TopicRecorder('/scan', LaserScan), TopicRecorder('/odom', Odometry)
    collisions = TopicRecorder('/collisions', UInt32)
    launched = session.launch('move_turtlebot3', 'avoid_obstacle.launch', params=LOCK_STEP,
                              real_time_factor=AVOID_FACTOR)

    def poses():
        return [(odom.header.stamp.to_sec(), odom.pose.pose.position.x, odom.pose.pose.position.y, 0.0)
                for odom in odoms.messages()]

    def stopped_at_the_wall():
        return (scans.messages() and scans.messages()[-1].ranges[0] <= 0.5 and len(poses()) > 1
                and path_length(_odom_points(odoms)) > 1.0 and driving.stopped_for(poses(), STOP_WATCH_S))

    wait_until(stopped_at_the_wall, 60, 'avoid_obstacle to stop in front of the wall for %g simulated seconds'
               % STOP_WATCH_S)
    front = driving.front_median(scans.messages(), STOP_WATCH_S)
    driven = path_length(_odom_points(odoms))
    hits = _collisions(collisions)
    session.stop(launched)
    lines = ['avoid_obstacle drove %.2f m and stopped %.3f m from the wall (front beam, median over the stop); '
             'collisions: %d' % (driven, front, hits)]

    odoms.clear()
    clock = TopicRecorder('/clock', Clock)
    picture = session.picture('move_turtlebot3-wander.png')
    launched = session.launch('move_turtlebot3', 'wander.launch', params=LOCK_STEP,
                              real_time_factor=WANDER_FACTOR, picture_png=picture)
    wait_until(lambda: clock.messages() and clock.messages()[-1].clock.to_sec() >= 120.0, 60,
               'wander to run 120 simulated seconds')
    session.call_trigger('/fake_tb3/save_picture')
    lines.append('wander.py drove %.1f m in 120 simulated seconds in turtlebot3_world; collisions: %d'
                 % (path_length(_odom_points(odoms)), _collisions(collisions)))
    session.stop(launched)
    for recorder in (scans, odoms, collisions, clock):
        recorder.close()
    return LabReport(lines, [picture])


def turtlebot3_rviz(session):
    """001: rviz shows the TurtleBot3 model and its laser scan as red points (on a virtual screen).

    rviz is started once more if a signal killed it before it drew (course_testing.rviz says why);
    the summary says so."""
    if not can_make_screens():
        return LabReport(['no screenshot: Xvfb or ImageMagick is missing (tools/setup.sh installs them)'], [])
    screenshot = session.picture('rviz.png')
    world = session.launch('turtlebot3_gazebo', 'turtlebot3_world.launch')
    with VirtualScreen() as screen:
        rviz, notes = rviz_until_drawn(
            lambda: session.launch('turtlebot3_gazebo', 'turtlebot3_gazebo_rviz.launch',
                                   env=screen.environment(session.env)),
            session.stop, screen, screenshot, red_at_least=300)
        red = red_pixels(screenshot)
        session.stop(rviz)
    session.stop(world)
    return LabReport(notes + ['rviz drew the robot model and the scan: %d laser-red pixels' % red], [screenshot])


LABS = [
    Lab('square', 'turtlesim draws a square (draw_square)', turtlesim_square),
    Lab('turtle', 'my_turtle drives forward and prints the pose', my_turtle_pose),
    Lab('teleop', 'keyboard teleop -> my_turtle_node -> turtle1', my_turtle_teleop),
    Lab('report', 'the report\'s square and triangle (exercise 5)', report_shapes),
    Lab('laser', 'TurtleBot3 laser printout (laser_data.py)', turtlebot3_laser),
    Lab('avoid', 'TurtleBot3 obstacle avoidance (avoid_obstacle.py, wander.py)',
        turtlebot3_avoid),
    Lab('rviz', 'rviz with the TurtleBot3 model and the laser scan', turtlebot3_rviz),
]
