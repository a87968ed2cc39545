"""The simulated TurtleBot3 as fake_tb3 publishes it: odometry (world pose, simulated time),
scans, collisions, the commands and the clock, recorded; and who published them or called its
services.

Two sources: fake_tb3's own record (course_common.sim_record), which the grader gives each run, so
that what the checks judge is what the simulator did and nothing a node published; or, for the
course's tests, fake_tb3's topics. Either way a node that publishes on fake_tb3's topics is named,
by what the master and the connection tell, never by the name the sender gives itself."""
import bisect
import math
import struct

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import UInt32

from course_checks.recorded import PublisherLook, RecordedTopic, Records
from course_checks.callers import ServiceCallWatch, sender
from course_checks.figures import path_length
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import poll_until

SIMULATOR = '/fake_tb3'
# The topics only fake_tb3 publishes on (the checks judge by them).
OWNED_TOPICS = ('/odom', '/scan', '/collisions', '/clock')
# fake_tb3's pose entries (fake_tb3.node.RECORDED_POSE): x, y, yaw, linear, angular.
RECORDED_POSE = struct.Struct('<5d')


def node_names():
    """The nodes the master knows (publishing, subscribing or serving); none while it does not
    answer (a submission took every process of its sandbox, say)."""
    try:
        publishers, subscribers, services = rosgraph.Master(rospy.get_name()).getSystemState()
    except OSError:
        return set()
    return {node for _, nodes in publishers + subscribers + services for node in nodes}


def left_the_graph(names):
    """None of the nodes `names` is known to the master any more (roscpp and rospy leave the graph
    first on Ctrl-C: what is left of them is their exit)."""
    return not node_names() & names


def senders(recorder):
    """The nodes that sent the messages a TopicRecorder kept (by the connection each came by)."""
    return {sender(message) for message in recorder.messages()}


class SimRecord:
    """What fake_tb3 recorded of its robot, read as it comes: poses (sim time s, x, y, yaw), scans
    (wall time sent, LaserScan), the collision count, the commands it applied (sim time s, linear,
    angular, sender) and the calls of its services (service, caller as the caller says)."""

    def __init__(self, path):
        self.records = Records([path])
        self.scans = RecordedTopic(self.records, 'scan', LaserScan)
        self._poses = []

    def poses(self):
        new = self.records.entries('pose')[len(self._poses):]
        self._poses += [(entry.sim_time,) + RECORDED_POSE.unpack(entry.payload)[:3] for entry in new]
        return list(self._poses)

    def collisions(self):
        told = self.records.events('collisions')
        return told[-1]['count'] if told else None

    def commands(self):
        return [(entry.sim_time, fields['linear'], fields['angular'], fields['sender'])
                for entry, fields in ((entry, entry.fields()) for entry in self.records.entries('command'))]

    def command_senders(self, but=None):
        """The senders of the commands applied, sorted; with `but`, those that are not that node."""
        return sorted({command['sender'] for command in self.records.events('command')
                       if but is None or but not in command['nodes']})

    def first_command_of(self, node):
        """The simulated time at which fake_tb3 applied the first command that came from `node` (the
        master's registration at the connection's other end), None if it applied none."""
        return next((entry.sim_time for entry in self.records.entries('command')
                     if node in entry.fields()['nodes']), None)

    def put_back(self):
        """(simulated time, fields) of the grader's put-back (fake_tb3.put_back), None before it."""
        entries = self.records.entries('put_back')
        return (entries[0].sim_time, entries[0].fields()) if entries else None

    def service_calls(self):
        return self.records.service_calls()


class RobotWatch:
    """Everything the checks look at: from fake_tb3's record when `record` names its file (the
    grader's runs), else from fake_tb3's topics (the course's tests)."""

    def __init__(self, cmd_vel='/cmd_vel', record=None):
        self._record = SimRecord(record) if record else None
        self._publishers = PublisherLook(OWNED_TOPICS, [SIMULATOR]) if record else None
        self._recorders = []
        if not record:
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
        """Forget everything: call between two runs of the simulator (topics only)."""
        for recorder in self._recorders:
            recorder.clear()
        self._poses_so_far = []

    def close(self):
        for recorder in self._recorders:
            recorder.close()
        if self._publishers:
            self._publishers.look(0)
            self._publishers.close()

    def drain(self, seconds):
        """Once the simulator and the node have ended: wait until every message they sent has been
        recorded (each connection read to its end; the record read to its end), at most `seconds`.
        Whether it was."""
        if self._record:
            self._record.poses()
            self._publishers.look(0)
            return True
        topics = [self._odom, self._scans, self._collisions, self._commands, self._clock]
        return poll_until(lambda: not any(recorder.subscriber.get_num_connections() for recorder in topics),
                          seconds)

    def impostors(self, simulator=SIMULATOR):
        """Topics the simulator owns (odom, scan, collisions, clock) on which another node
        published: {topic: sorted node names}. From the record: the nodes the master listed as
        their publishers (what they sent never counted); from the topics: the nodes at the other
        end of the connections messages came by."""
        if self._record:
            return {topic: sorted(nodes) for topic, nodes in sorted(self._publishers.look(0).items())}
        found = {}
        for name, recorder in (('odom', self._odom), ('scan', self._scans), ('collisions', self._collisions),
                               ('clock', self._clock)):
            others = senders(recorder) - {simulator}
            if others:
                found[name] = sorted(others)
        return found

    def service_calls(self):
        """[(service, caller)] of fake_tb3's services, as fake_tb3 noted them: the lab uses none."""
        if self._record:
            return self._record.service_calls()
        return self._service_calls.calls()

    @property
    def collisions(self):
        """The simulator's latest collision count, None before it told one."""
        if self._record:
            return self._record.collisions()
        latest = self._collisions.latest()
        return None if latest is None else latest.data

    def _poses(self):
        """(sim time s, x, y, yaw) of every odometry message (every pose recorded)."""
        if self._record:
            return self._record.poses()
        for odom in self._odom.messages(len(self._poses_so_far)):
            orientation = odom.pose.pose.orientation
            self._poses_so_far.append((odom.header.stamp.to_sec(), odom.pose.pose.position.x,
                                       odom.pose.pose.position.y, 2 * math.atan2(orientation.z, orientation.w)))
        return list(self._poses_so_far)

    def _timed_commands(self):
        """(sim time s, linear, angular) of every command: as fake_tb3 applied it (the record), or
        the latest clock when it arrived, None before the first (the topics)."""
        if self._record:
            return [(t, linear, angular) for t, linear, angular, _ in self._record.commands()]
        clock = self._clock.entries()
        clock_arrivals = [arrival for arrival, _ in clock]
        commands = []
        for arrival, command in self._commands.entries():
            ticks = bisect.bisect_right(clock_arrivals, arrival)
            sim_time = clock[ticks - 1][1].clock.to_sec() if ticks else None
            commands.append((sim_time, command.linear.x, command.angular.z))
        return commands

    def scan_entries(self):
        """(time.monotonic() the scan was sent (the record) or heard (the topics), LaserScan) of
        every scan."""
        if self._record:
            return self._record.scans.entries()
        return self._scans.entries()

    def command_senders(self, but=None):
        """The senders of the commands fake_tb3 applied, as it named them ('NODE (uid N)'); with
        `but`, those other than that node (the record only)."""
        if self._record:
            return self._record.command_senders(but)
        return []

    def first_command_of(self, node):
        """The simulated time at which fake_tb3 applied the first command of `node`, None if it
        applied none (the record only: None from the topics)."""
        if self._record:
            return self._record.first_command_of(node)
        return None

    def put_back(self):
        """(simulated time, {'still_since', 'x', 'y', 'to_x', 'to_y'}) of the grader's put-back, None
        before it (the record only: None from the topics)."""
        return self._record.put_back() if self._record else None

    def copy(self, name):
        """What was recorded so far: 'poses', 'scans' or 'commands'."""
        return {'poses': self._poses, 'scans': lambda: [scan for _, scan in self.scan_entries()],
                'commands': self._timed_commands}[name]()

    def running(self):
        """The simulator publishes odometry and scans and has told its collision count."""
        if self._record:
            return bool(self._record.poses() and self._record.scans.count() and self._record.collisions() is not None)
        return bool(self._odom.count() and self._scans.count() and self.collisions is not None)

    def now(self):
        """Simulated time of the latest odometry."""
        if self._record:
            return self._record.poses()[-1][0]
        return self._odom.latest().header.stamp.to_sec()

    def poses_since(self, start):
        return [pose for pose in self.copy('poses') if pose[0] >= start]

    def front_range(self):
        scans = self.scan_entries()
        return scans[-1][1].ranges[0]


def travelled(poses):
    """Distance driven along (sim time, x, y, yaw) poses, in metres."""
    return path_length([(x, y) for _, x, y, _ in poses])


def largest_move(poses):
    """How far the robot got from the first of these poses at most."""
    return max(math.hypot(x - poses[0][1], y - poses[0][2]) for _, x, y, _ in poses)
