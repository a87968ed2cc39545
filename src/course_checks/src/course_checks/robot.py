"""The simulated TurtleBot3 as fake_tb3 publishes it: odometry (world pose, simulated time),
scans, collisions, the commands and the clock, recorded; and who published them or called its
services."""
import bisect
import math

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import UInt32

from course_checks.service_calls import ServiceCallWatch, sender
from course_testing.recording import TopicRecorder, path_length
from course_testing.waiting import poll_until

SIMULATOR = '/fake_tb3'


def node_names():
    """The nodes the master knows (publishing, subscribing or serving); none while it does not
    answer (a submission took every process of its sandbox, say)."""
    try:
        publishers, subscribers, services = rosgraph.Master(rospy.get_name()).getSystemState()
    except OSError:
        return set()
    return {node for _, nodes in publishers + subscribers + services for node in nodes}


def senders(recorder):
    """The nodes that sent the messages a TopicRecorder kept (rospy notes each message's sender)."""
    return {sender(message) for message in recorder.messages()}


class RobotWatch:
    """Everything the checks look at, recorded from fake_tb3's topics."""

    def __init__(self, cmd_vel='/cmd_vel'):
        self._odom = TopicRecorder('/odom', Odometry)
        self._scans = TopicRecorder('/scan', LaserScan)
        self._collisions = TopicRecorder('/collisions', UInt32)
        self._commands = TopicRecorder(cmd_vel, Twist)
        self._clock = TopicRecorder('/clock', Clock)
        self._service_calls = ServiceCallWatch(SIMULATOR)
        self._recorders = [self._odom, self._scans, self._collisions, self._commands, self._clock,
                           self._service_calls]
        self._poses_so_far = []  # the odometry converted so far: checks poll the poses often

    def reset(self):
        """Forget everything: call between two runs of the simulator."""
        for recorder in self._recorders:
            recorder.clear()
        self._poses_so_far = []

    def close(self):
        for recorder in self._recorders:
            recorder.close()

    def drain(self, seconds):
        """Once the simulator and the node have ended: wait until every message they sent has been
        recorded (each connection read to its end), at most `seconds`. Whether it was."""
        topics = [self._odom, self._scans, self._collisions, self._commands, self._clock]
        return poll_until(lambda: not any(recorder.subscriber.get_num_connections() for recorder in topics),
                          seconds)

    def impostors(self, simulator=SIMULATOR):
        """Topics the simulator owns (odom, scan, collisions, clock) on which another node sent
        messages that were recorded: {topic: sorted node names}."""
        found = {}
        for name, recorder in (('odom', self._odom), ('scan', self._scans), ('collisions', self._collisions),
                               ('clock', self._clock)):
            others = senders(recorder) - {simulator}
            if others:
                found[name] = sorted(others)
        return found

    def service_calls(self):
        """[(service, caller)] of fake_tb3's services, as fake_tb3 noted them: the lab uses none."""
        return self._service_calls.calls()

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

    def running(self):
        """The simulator publishes odometry and scans and has told its collision count."""
        return bool(self._odom.count() and self._scans.count() and self.collisions is not None)

    def now(self):
        """Simulated time of the latest odometry."""
        return self._odom.latest().header.stamp.to_sec()

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
