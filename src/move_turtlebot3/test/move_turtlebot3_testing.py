"""Test helpers: run this package's launch files (as a student would, with roslaunch) against the
test's master, and watch the simulated robot through fake_tb3's topics."""
import bisect
import math
import os
import subprocess
import threading
import unittest

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import UInt32

from course_testing.processes import stop_process_group
from course_testing.recording import TopicRecorder, path_length
from course_testing.waiting import wait_until


def node_names():
    publishers, subscribers, services = rosgraph.Master(rospy.get_name()).getSystemState()
    return {node for _, nodes in publishers + subscribers + services for node in nodes}


class Launch:
    """roslaunch of one of this package's launch files (or a lone node), output collected."""

    def __init__(self, *argv):
        # Unbuffered, so that what the nodes print reaches us line by line, as in a terminal.
        env = dict(os.environ, PYTHONUNBUFFERED='1')
        self.process = subprocess.Popen(list(argv), stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, env=env, text=True,
                                        start_new_session=True)
        self._lines = []
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    @classmethod
    def package_file(cls, launch_file, **args):
        return cls('roslaunch', 'move_turtlebot3', launch_file,
                   *['%s:=%s' % item for item in sorted(args.items())])

    def _read(self):
        for line in self.process.stdout:
            with self._lock:
                self._lines.append(line.rstrip('\n'))

    @property
    def lines(self):
        with self._lock:
            return list(self._lines)

    @property
    def output(self):
        return '\n'.join(self.lines)

    def wait_for_output(self, text, timeout):
        return wait_until(lambda: text in self.output, timeout, what='%r in the output' % text)

    def stop(self):
        """Ctrl-C, as in the terminal; roslaunch stops its nodes. Kill only if it hangs."""
        stop_process_group(self.process, 30)
        self._reader.join(5)


class RobotWatch:
    """Everything the tests look at, recorded from fake_tb3's topics: odometry (world pose, sim
    time), scans, collisions, the commands and the clock."""

    def __init__(self, cmd_vel='/cmd_vel'):
        self._odom = TopicRecorder('/odom', Odometry)
        self._scans = TopicRecorder('/scan', LaserScan)
        self._collisions = TopicRecorder('/collisions', UInt32)
        self._commands = TopicRecorder(cmd_vel, Twist)
        self._clock = TopicRecorder('/clock', Clock)
        self._recorders = [self._odom, self._scans, self._collisions, self._commands, self._clock]
        self._poses_so_far = []  # the odometry converted so far: tests poll the poses often

    def reset(self):
        """Forget everything: call between two runs of the simulator."""
        for recorder in self._recorders:
            recorder.clear()
        self._poses_so_far = []

    def close(self):
        for recorder in self._recorders:
            recorder.close()

    @property
    def collisions(self):
        """The simulator's latest collision count, None before it told one."""
        latest = self._collisions.latest()
        return None if latest is None else latest.data

    def _poses(self):
        """(sim time s, x, y, yaw) of every odometry message."""
        for odom in self._odom.messages(len(self._poses_so_far)):
            orientation = odom.pose.pose.orientation
            self._poses_so_far.append((odom.header.stamp.to_sec(), odom.pose.pose.position.x,
                                       odom.pose.pose.position.y, 2 * math.atan2(orientation.z, orientation.w)))
        return list(self._poses_so_far)

    def _timed_commands(self):
        """(sim time s of the latest clock when it arrived, or None; linear, angular) of every command."""
        clock = self._clock.entries()
        clock_arrivals = [arrival for arrival, _ in clock]
        commands = []
        for arrival, command in self._commands.entries():
            ticks = bisect.bisect_right(clock_arrivals, arrival)
            sim_time = clock[ticks - 1][1].clock.to_sec() if ticks else None
            commands.append((sim_time, command.linear.x, command.angular.z))
        return commands

    def copy(self, name):
        """What was recorded so far: 'poses', 'scans' or 'commands'."""
        return {'poses': self._poses, 'scans': self._scans.messages, 'commands': self._timed_commands}[name]()

    def wait_until_running(self, timeout=60):
        """Until the simulator publishes odometry and scans and tells its collision count."""
        wait_until(lambda: self._odom.count() and self._scans.count() and self.collisions is not None,
                   timeout, what='odom, scan and collisions from fake_tb3')

    def now(self):
        """Simulated time of the latest odometry."""
        return self._odom.latest().header.stamp.to_sec()

    def wait_sim_seconds(self, seconds, timeout):
        end = self.now() + seconds
        wait_until(lambda: self.now() >= end, timeout, what='%.0f simulated seconds' % seconds)

    def poses_since(self, start):
        return [pose for pose in self.copy('poses') if pose[0] >= start]

    def front_range(self):
        return self._scans.latest().ranges[0]


def travelled(poses):
    """Distance driven along (sim time, x, y, yaw) poses, in metres."""
    return path_length([(x, y) for _, x, y, _ in poses])


def largest_move(poses):
    """How far the robot got from the first of these poses at most."""
    return max(math.hypot(x - poses[0][1], y - poses[0][2]) for _, x, y, _ in poses)


class LabTestCase(unittest.TestCase):
    """A test case with a RobotWatch, and a Launch (self.launch) stopped at its end."""

    def setUp(self):
        self.watch = RobotWatch()
        self.launch = None

    def tearDown(self):
        if self.launch is not None:
            self.launch.stop()
            # Kept in the test's log (and in the result file), to see what went on when it fails.
            print('--- output of %s:\n%s' % (self._testMethodName, self.launch.output))
        self.watch.close()


class LoneNode:
    """One of this package's scan nodes run alone, on scans and commands topics of the test's own."""

    def __init__(self, script):
        self.launch = Launch('rosrun', 'move_turtlebot3', script,
                             '/scan:=/odd_scan', '/cmd_vel:=/odd_cmd_vel')
        self._publisher = rospy.Publisher('/odd_scan', LaserScan, queue_size=1)
        self.commands = []
        self._listener = rospy.Subscriber('/odd_cmd_vel', Twist, self.commands.append)
        wait_until(lambda: self._publisher.get_num_connections() > 0
                   and self._listener.get_num_connections() > 0,
                   timeout=30, what='%s to connect' % script)

    def answer_to(self, scan):
        """Publish one scan and return the (linear, angular) command the node answers with."""
        count = len(self.commands)

        def answered():
            if len(self.commands) > count:
                return True
            # (Again after half a second: the node's first answers can leave before its publisher
            # has taken in our fresh connection.)
            self._publisher.publish(scan)
            return False

        wait_until(answered, timeout=10, what='an answer to a scan', poll=0.5)
        return self.commands[-1].linear.x, self.commands[-1].angular.z

    @property
    def output(self):
        return self.launch.output

    def stop(self):
        self._listener.unregister()
        self._publisher.unregister()
        self.launch.stop()
