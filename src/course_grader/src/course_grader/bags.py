"""Each graded run as a rosbag, made from the simulator's own record (course_common.sim_record): the
topics as the simulator published them and the commands as it applied them, each at the simulated
time the simulator recorded (never a stamp a node wrote), so that `rosbag play`, rviz, the report's
player and course_web's replay.launch show the run the checks judged. Beside it, `<run>.marks.json`:
the moments the checks judged ([{"t": simulated s, "what": sentence, "criterion": id}]).

What a bag holds (the topics are the simulator's own names):
- fake_tb3: /odom (nav_msgs/Odometry: each pose recorded, frames odom -> base_footprint), /scan
  (sensor_msgs/LaserScan: the bytes sent), /cmd_vel (geometry_msgs/Twist: each command as applied,
  the connection's callerid the sender as fake_tb3 told it, 'NODE (uid N)'), /collisions
  (std_msgs/UInt32: each count told), /fake_tb3/service_calls (std_msgs/String, JSON
  {"service", "caller"}); the run's world and model in /fake_tb3/run (std_msgs/String, JSON, once).
- turtlesim (node /NAME): /TURTLE/pose (turtlesim/Pose, every tick), /TURTLE/cmd_vel
  (geometry_msgs/Twist, callerid the sender), /TURTLE/pen (turtlesim/SetPenRequest: each set_pen as
  turtlesim applied it), /NAME/canvas (std_msgs/String, JSON {"background": [r, g, b]}: the canvas
  filled, at the start and at each /clear or /reset), /NAME/turtles (std_msgs/String, JSON
  {"names": [...]}: the turtles whenever they changed), /NAME/service_calls.

Bounded: a topic with more than its kind's cap (TOPIC_CAPS) keeps an even sample over the whole
run (the first and last message included), at most MAX_TOPICS topics and MAX_MESSAGES messages
per bag; LZ4-compressed.
Writing one is the trusted side's (a bag that cannot be written costs no criterion: the session
notes it in the result's `notes`). Needs no master."""
import functools
import json
import math
import os
import time

import rosbag
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String, UInt32
from turtlesim.msg import Pose
from turtlesim.srv import SetPenRequest

from course_checks.robot import RECORDED_POSE as FAKE_TB3_POSE
from course_common.sim_record import RecordReader

# At most this many messages of one topic in a bag, by the topic's last name; a topic with more
# keeps an even sample. The scans dominate: 600 of them are about 1.7 MB before compression.
TOPIC_CAPS = {'odom': 6000, 'scan': 600, 'pose': 6000, 'cmd_vel': 6000}
OTHER_CAP = 2000
MAX_MESSAGES = 15000     # in one bag: about 1.5 MB at most (measured: a 30x run of 60 s, 1800 simulated s)
MAX_TOPICS = 40          # a submission that spawns a thousand turtles gets the first ones' topics
BAG_SECONDS = 5.0        # wall seconds at most to make a run's bag (within the run's margin, wall_limit)
COMPRESSION = 'lz4'      # rosbag's own; on Debian python3-rosbag reads and writes it (roslz4)
BAG_SUFFIX = '.bag'
MARKS_SUFFIX = '.marks.json'


def _time(sim_ns):
    return rospy.Time(0, max(1, sim_ns))   # rosbag play skips a message at time 0 (its "invalid time")


def _json(**fields):
    return String(json.dumps(fields, sort_keys=True))


def _twist(fields):
    twist = Twist()
    twist.linear.x, twist.angular.z = float(fields['linear']), float(fields['angular'])
    return twist


def _sender(fields):
    return {'callerid': str(fields.get('sender', '?'))}


def _odometry(payload, t, prefix):
    x, y, yaw, linear, angular = FAKE_TB3_POSE.unpack(payload)
    odom = Odometry()
    odom.header.stamp = t
    odom.header.frame_id, odom.child_frame_id = prefix + 'odom', prefix + 'base_footprint'
    odom.pose.pose.position.x, odom.pose.pose.position.y = x, y
    odom.pose.pose.orientation.z, odom.pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    odom.twist.twist.linear.x, odom.twist.twist.angular.z = linear, angular
    return odom


def _deserialized(message_class, payload):
    return message_class().deserialize(payload)


def fake_tb3_messages(entries, world=None, model=None, prefix=''):
    """[(topic, message, time, connection header or None)] of fake_tb3's record entries, in the
    record's order; `world` and `model`, the run's settings, on /fake_tb3/run first. The many
    (odometry, scans) come as functions that make the message: only those kept are made."""
    messages = []
    if world is not None or model is not None:
        first = entries[0].sim_ns if entries else 0
        messages.append(('/fake_tb3/run', _json(world=world, model=model), _time(first), None))
    for entry in entries:
        t = _time(entry.sim_ns)
        if entry.name == prefix + 'pose':
            messages.append(('/' + prefix + 'odom', functools.partial(_odometry, entry.payload, t, prefix), t, None))
        elif entry.name == prefix + 'scan':
            messages.append(('/' + prefix + 'scan', functools.partial(_deserialized, LaserScan, entry.payload), t, None))
        elif entry.name == 'command':
            fields = entry.fields()
            if fields.get('robot', '') == prefix.rstrip('/'):
                messages.append(('/' + prefix + 'cmd_vel', _twist(fields), t, _sender(fields)))
        elif entry.name == 'collisions':
            fields = entry.fields()
            if fields.get('robot', '') == prefix.rstrip('/'):
                messages.append(('/' + prefix + 'collisions', UInt32(int(fields['count'])), t, None))
        elif entry.name == 'service_call':
            messages.append(('/fake_tb3/service_calls', String(entry.payload.decode()), t, None))
    return messages


def turtlesim_messages(entries, node_name):
    """[(topic, message, time, connection header or None)] of the record entries of the turtlesim
    node `node_name` (full name, as /turtlesim), in the record's order (the poses as functions
    that make the message, as fake_tb3_messages)."""
    namespace = node_name.rsplit('/', 1)[0]
    messages = []
    pose_topics = {}   # turtle name: its pose topic (resolved, as the record names it)

    def turtle_topic(name, last):
        base = pose_topics.get(name)
        if base is None:
            base = name if name.startswith('/') else '%s/%s' % (namespace, name)
        else:
            base = base[:-len('/pose')]
        return '%s/%s' % (base, last)
    for entry in entries:
        t = _time(entry.sim_ns)
        if entry.name.endswith('/pose') and entry.name.startswith('/'):
            pose_topics.setdefault(entry.name[:-len('/pose')].rsplit('/', 1)[-1], entry.name)
            messages.append((entry.name, functools.partial(_deserialized, Pose, entry.payload), t, None))
        elif entry.name == 'command':
            fields = entry.fields()
            messages.append((turtle_topic(fields['turtle'], 'cmd_vel'), _twist(fields), t, _sender(fields)))
        elif entry.name == 'pen':
            fields = entry.fields()
            pen = SetPenRequest(int(fields['r']), int(fields['g']), int(fields['b']), int(fields['width']),
                                int(bool(fields['off'])))
            messages.append((turtle_topic(fields['turtle'], 'pen'), pen, t, None))
        elif entry.name in ('clear', 'turtles', 'service_call'):
            topic = {'clear': 'canvas', 'turtles': 'turtles', 'service_call': 'service_calls'}[entry.name]
            messages.append(('%s/%s' % (node_name, topic), String(entry.payload.decode()), t, None))
    return messages


def bounded(messages):
    """`messages` with at most MAX_TOPICS topics (the first seen), each topic's cap, and
    MAX_MESSAGES in all (the caps shrunk alike): a topic over its cap keeps an even sample over the
    whole run, its first and last messages included."""
    by_topic = {}
    for index, item in enumerate(messages):
        by_topic.setdefault(item[0], []).append(index)
    caps = {topic: min(len(indices), TOPIC_CAPS.get(topic.rsplit('/', 1)[-1], OTHER_CAP))
            for topic, indices in list(by_topic.items())[:MAX_TOPICS]}
    total = sum(caps.values())
    if total > MAX_MESSAGES:
        caps = {topic: max(2, cap * MAX_MESSAGES // total) for topic, cap in caps.items()}
    kept = set()
    for topic, cap in caps.items():
        indices = by_topic[topic]
        if len(indices) <= cap:
            kept.update(indices)
        else:
            last = len(indices) - 1
            kept.update(indices[round(i * last / (cap - 1))] for i in range(cap))
    return [item for index, item in enumerate(messages) if index in kept]


class BagError(OSError):
    """A bag or marks file that cannot be written: one sentence naming it."""


def _new_file(path):
    """A new file at `path` (never one that exists, never through a link), open for writing."""
    return os.fdopen(os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600), 'w+b')


def _written(path, write):
    """write(stream) into a new file at `path`; OSError naming the file when it cannot be (the
    part written removed: a bag cut short is no bag)."""
    try:
        stream = _new_file(path)
    except OSError as error:
        raise BagError('cannot write %s: %s' % (os.path.basename(path), error.strerror or error)) from error
    try:
        with stream:
            write(stream)
    except (OSError, rosbag.ROSBagException) as error:
        os.remove(path)
        raise BagError('cannot write %s: %s' % (os.path.basename(path), _why(error))) from error


def _why(error):
    """What the system said of a failed write, below what rosbag made of it ('error compressing'
    of a full disk: No space left on device)."""
    seen = error
    while seen is not None:
        if getattr(seen, 'strerror', None):
            return seen.strerror
        seen = seen.__cause__ or seen.__context__
    return str(error) or type(error).__name__


def write_bag(path, messages, deadline=None):
    """The messages (bounded) into a new bag at `path`, by time. BagError when it cannot be written,
    or not by `deadline` (time.monotonic()): the run's time is the grading's."""
    ordered = sorted(bounded(messages), key=lambda item: item[2])

    def write(stream):
        with rosbag.Bag(stream, 'w', compression=COMPRESSION) as bag:
            for index, (topic, message, t, header) in enumerate(ordered):
                if deadline is not None and index % 500 == 0 and time.monotonic() > deadline:
                    raise rosbag.ROSBagException('not written within %g s' % BAG_SECONDS)
                if callable(message):
                    message = message()
                if header:   # a connection of its own per sender, with what rosbag needs of one
                    header = dict(header, topic=topic, type=message._type, md5sum=message._md5sum,
                                  message_definition=message._full_text)
                bag.write(topic, message, t, connection_header=header)
    _written(path, write)


def read_record(path):
    """Every entry of a record file (a simulator's, after it stopped)."""
    return RecordReader(path).read_new()


def write_marks(path, marks):
    """The judged moments, [{"t", "what", "criterion"}], sorted by time, into a new file."""
    text = json.dumps(sorted(marks, key=lambda mark: mark['t']), indent=1).encode()
    _written(path, lambda stream: stream.write(text))


def mark(t, what, criterion):
    """One judged moment: at `t` simulated seconds, a sentence, the criterion it decided."""
    return {'t': round(float(t), 4), 'what': what, 'criterion': criterion}


class Marks(list):
    """The moments the checks judged in one run (marks, as write_marks takes them)."""

    def add(self, t, what, criterion):
        """A moment at `t` simulated seconds; one that is no time is left out: a mark never costs a verdict."""
        try:
            self.append(mark(t, what, criterion))
        except (TypeError, ValueError):
            pass


def collisions(entries, robot=''):
    """[(simulated s, count)] of each collision fake_tb3 recorded (each rise of the robot's count)."""
    found, last = [], 0
    for entry in entries:
        if entry.name == 'collisions':
            fields = entry.fields()
            if fields.get('robot', '') == robot and fields['count'] > last:
                found.append((entry.sim_time, fields['count']))
            if fields.get('robot', '') == robot:
                last = fields['count']
    return found
