"""turtlesim_node: the ROS interface of the world in turtlesim.world.

The layer is made of:
- TurtlesimNode (this module): the world, the tick thread, the global services (clear, reset,
  spawn, kill) and the turtles' interfaces;
- TurtleInterface (this module): one turtle's topics (pose, color_sensor, cmd_vel) and services
  (set_pen, teleport_absolute, teleport_relative);
- turtlesim.ticks: when the ticks fall (wall clock, or a simulated clock with /use_sim_time);
- turtlesim.canvas_outputs: ~save_canvas, ~canvas and the PNG at shutdown; turtlesim.window: the
  window. They read pictures through TurtlesimNode.snapshot() and never change the world.

Threads: one tick thread owns the world and steps it at each tick. ROS callbacks (cmd_vel, service
calls) never touch the world: they submit a request (course_common.request_queue) that the tick
thread runs between two ticks, and a service call waits for its request and returns its result.
Creating and removing a turtle's topics and services (slow calls to the master) happens in the
service thread, so ticks stay on time. A turtle's topics and services are made all or none (a spawn
that fails half-way removes what it made, and the turtle) and a kill gives all of them back; the
topics share one epoll (turtlesim.shared_poll), so a turtle holds no open file of its own. Only the
turtles someone listens to are published (their publishers tell when a subscriber comes or goes),
so 2000 turtles cost little more than the ones watched; the tick thread writes their poses and
colours to the subscribers' sockets itself (course_common.batched_writes), so a publish wakes no
writer thread of rospy's. Pictures copy the world under a lock and are drawn outside it.
"""
import itertools
import os
import signal
import struct
import sys
import threading
import time

import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty, EmptyResponse

from course_common import batched_writes, prompt_shutdown, sim_record_ros
from course_common.request_queue import RequestQueue, Stopped
from course_common.service_calls_ros import ServiceCallTopic
from turtlesim import command_line, picture, shared_poll
from turtlesim.canvas_outputs import CanvasOutputs
from turtlesim.holdings import (LOW_FILE_LIMIT, Holdings, capacity_note, open_file_count, open_file_limit,
                                raise_open_file_limit, spawn_refusal)
from turtlesim.msg import Color, Pose
from turtlesim.scene_topic import SceneTopic
from turtlesim.srv import (Kill, KillResponse, SetPen, SetPenResponse, Spawn, SpawnResponse,
                           TeleportAbsolute, TeleportAbsoluteResponse, TeleportRelative,
                           TeleportRelativeResponse)
from turtlesim.ticks import make_ticks
from turtlesim.world import DEFAULT_BACKGROUND, FLOAT32_MAX, TurtlesimError, World

SHUTDOWN_POLL = 0.1  # how often a waiting service call checks whether the node is shutting down
# A pose in the grader's record (course_common.sim_record), as the pose topic carries it: x, y,
# theta, linear and angular velocity, float32 each.
RECORDED_POSE = struct.Struct('<5f')
RECORD_FLUSH_SECONDS = 0.02   # wall seconds at most before the record's entries reach the judge


class RosLog:
    """The world's log object, writing to rosout."""

    @staticmethod
    def info(text):
        rospy.loginfo(text)

    @staticmethod
    def warning(text):
        rospy.logwarn(text)


def _float32(value):
    """Fit a value into a float32 message field (turtlesim/Pose): huge velocities saturate."""
    return min(max(value, -FLOAT32_MAX), FLOAT32_MAX)


def _batched(publisher):
    batched_writes.batch(publisher)
    return publisher


def _unregister(topic):
    topic.unregister()


def _shut_down(service):
    service.shutdown()


class TurtleInterface:
    """The topics and services of one turtle (under the turtle's name, relative to the node).

    Made all or none: if one cannot be made, those already made are removed and the error raised."""

    def __init__(self, node, name):
        self.name = name
        self.holdings = Holdings()
        self.pose = self.color = None
        self._node = node  # lists this turtle in node.watched while someone listens
        listener = _Listeners(self)
        self.pose, self.color, _, _, _, _ = self.holdings.take_all([
            ('pose publisher', lambda: _batched(rospy.Publisher(name + '/pose', Pose, queue_size=1,
                                                                subscriber_listener=listener)),
             _unregister),
            ('color_sensor publisher', lambda: _batched(rospy.Publisher(
                name + '/color_sensor', Color, queue_size=1, subscriber_listener=listener)), _unregister),
            ('cmd_vel subscriber',
             lambda: rospy.Subscriber(name + '/cmd_vel', Twist, node.on_cmd_vel, name, queue_size=1), _unregister),
            ('set_pen service', lambda: node.service(name + '/set_pen', SetPen, lambda req: node.set_pen(name, req)),
             _shut_down),
            ('teleport_absolute service',
             lambda: node.service(name + '/teleport_absolute', TeleportAbsolute,
                                  lambda req: node.teleport_absolute(name, req)), _shut_down),
            ('teleport_relative service',
             lambda: node.service(name + '/teleport_relative', TeleportRelative,
                                  lambda req: node.teleport_relative(name, req)), _shut_down),
        ])
        self.listened()  # a subscriber may have connected before both publishers existed

    def listened(self):
        """A pose or color_sensor subscriber came or went: (un)list this turtle for publishing."""
        if self.pose is None or self.color is None:
            return  # still being made: __init__ looks once both exist
        if self.pose.get_num_connections() or self.color.get_num_connections():
            self._node.watched[self.name] = self
        else:
            self._node.watched.pop(self.name, None)
        self._node.watched_changed()

    def close(self):
        """Give everything back; what cannot be is reported, and the rest is still given back."""
        self._node.watched.pop(self.name, None)
        self._node.watched_changed()
        for label, error in self.holdings.release_all():
            rospy.logwarn('Turtle [%s]: could not remove its %s: %s' % (self.name, label, error))

    def publish(self, turtle):
        """In the tick thread: the turtle's pose and colour to their subscribers (the thread's
        next flush of batched_writes sends them)."""
        if batched_writes.subscribed(self.pose):
            batched_writes.publish(self.pose, Pose(turtle.x, turtle.y, turtle.theta,
                                                   _float32(turtle.linear_velocity), _float32(turtle.wz)))
        if batched_writes.subscribed(self.color):
            batched_writes.publish(self.color, Color(*turtle.color))


class _Listeners(rospy.SubscribeListener):
    """Tells a turtle's interface when a subscriber of its pose or color_sensor comes or goes."""

    def __init__(self, interface):
        super().__init__()
        self.interface = interface

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        self.interface.listened()

    def peer_unsubscribe(self, topic_name, num_peers):
        self.interface.listened()


class TurtlesimNode:
    def __init__(self):
        shared_poll.install(rospy.topics)  # before any topic exists, rosout's included
        # What it did, for the grader (only when the grader names the file: course_common.sim_record),
        # each command with who sent it; without a record, rospy's receiving is left as it is.
        self.record = sim_record_ros.open_record()
        if self.record:
            sim_record_ros.install(rospy.topics)
        self._recorded = (None, 0.0, 0)   # (roster recorded, wall time of the last flush, tick ns)
        file_limit, _ = raise_open_file_limit()
        # Ctrl-C is handled in main(): rospy's own handler could run while this thread registers
        # with the master and wait for a lock that this very thread holds.
        rospy.init_node('turtlesim', disable_signals=True)
        prompt_shutdown.install()   # Ctrl-C ends it at once, as the original
        rospy.loginfo('Starting turtlesim with node name %s' % rospy.get_name())
        if file_limit < LOW_FILE_LIMIT:
            rospy.loginfo(capacity_note(file_limit, open_file_count() or 0))
        for channel, value in zip(('r', 'g', 'b'), DEFAULT_BACKGROUND):
            if not rospy.has_param('~background_' + channel):
                rospy.set_param('~background_' + channel, value)
        given = command_line.settings(rospy.myargv(sys.argv)[1:])
        self.ticks = make_ticks(given)
        self.started_background = self.read_background()   # for the record's first entry
        self.world = World(RosLog, self.started_background, name_key=rospy.resolve_name)
        self.world_lock = threading.Lock()  # held while the world changes and while it is copied
        self.scene_topic = SceneTopic(self.world)  # ~scene, for a web viewer
        self.requests = RequestQueue(expected=(TurtlesimError,),
                                     on_error=lambda error: rospy.logwarn_throttle(1.0, str(error)))
        self._registry_lock = threading.Lock()  # one spawn/kill/reset changes the interfaces at a time
        self.interfaces = {}  # turtle name -> TurtleInterface; replaced as a whole, never mutated
        self.watched = {}  # turtle name -> TurtleInterface of the turtles someone subscribes to
        self._watched_changes = itertools.count()
        self._watched_revision = next(self._watched_changes)  # changes whenever `watched` does
        self._published = (None, [])  # ((world.roster, watched revision), [(turtle, interface)])
        self.service_calls = ServiceCallTopic(self.note)  # who called which service: the grader's checks read it
        self._sync_interfaces()
        self._services = [
            self.service('clear', Empty, self.clear),
            self.service('reset', Empty, self.reset),
            self.service('spawn', Spawn, self.spawn),
            self.service('kill', Kill, self.kill),
        ]
        self.canvas_outputs = CanvasOutputs(self.snapshot, given.get('canvas_png'))
        self._tick_thread = threading.Thread(target=self._run_ticks, name='turtlesim-ticks', daemon=True)

    # --- parameters ---
    @staticmethod
    def read_background():
        """~background_r/g/b as a colour; a value that is not an int in 0..255 is reported and ignored."""
        colour = []
        for channel, default in zip(('r', 'g', 'b'), DEFAULT_BACKGROUND):
            value = rospy.get_param('~background_' + channel, default)
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 255:
                rospy.logwarn('Parameter %s must be an integer from 0 to 255, not %r: using %d'
                              % (rospy.resolve_name('~background_' + channel), value, default))
                value = default
            colour.append(value)
        return tuple(colour)

    # --- the tick thread ---
    def start(self):
        self._tick_thread.start()

    def _run_ticks(self):
        running = lambda: not rospy.is_shutdown()  # noqa: E731
        while running():
            now = self.ticks.wait(running)
            with self.world_lock:
                self.requests.run_pending(now)
                self.world.tick(now)
            for turtle, interface in self._watched_in_order():
                interface.publish(turtle)
            self.scene_topic.after_tick()  # flushes the poses too
            if self.record:
                self._record_tick(int(round(now * 1e9)))
        self.requests.fail_pending(TurtlesimError('turtlesim is shutting down'))
        if self.record:
            self.record.close()

    # --- the grader's record ---
    def _record_tick(self, tick_ns):
        """In the tick thread: every turtle's pose as its pose topic carries it (listened to or
        not), and the turtles whenever they changed."""
        wall = time.monotonic()
        roster, flushed, _ = self._recorded
        interfaces = self.interfaces
        for turtle in self.world.turtles():
            interface = interfaces.get(turtle.name)
            if interface is not None and interface.pose is not None:
                self.record.write(interface.pose.resolved_name, tick_ns, wall, RECORDED_POSE.pack(
                    turtle.x, turtle.y, turtle.theta, _float32(turtle.linear_velocity), _float32(turtle.wz)))
        if roster is None:   # the first tick: the background the canvas was filled with
            self.record.event('clear', tick_ns, wall, background=list(self.started_background))
        if roster != (self.world.roster, tuple(interfaces)):
            roster = (self.world.roster, tuple(interfaces))
            self.record.event('turtles', tick_ns, wall, names=sorted(interfaces))
        if wall - flushed >= RECORD_FLUSH_SECONDS:
            self.record.flush()
            flushed = wall
        self._recorded = (roster, flushed, tick_ns)

    def note(self, name, **fields):
        """An event of the record (when there is one), at the last tick's time."""
        if self.record:
            self.record.event(name, self._recorded[2], time.monotonic(), **fields)

    def drawn(self, name, now, **fields):
        """In the tick thread: an event of the record (when there is one) that changes what the pen
        draws (a pen set, the canvas cleared), at the time of the tick it applies in (`now`, s), so
        that a replay redraws the trails as turtlesim drew them."""
        if self.record:
            self.record.event(name, int(round(now * 1e9)), time.monotonic(), **fields)

    def join(self):
        self._tick_thread.join()

    def watched_changed(self):
        """Any thread: `watched` changed (itertools.count's next() is atomic)."""
        self._watched_revision = next(self._watched_changes)

    def _watched_in_order(self):
        """The turtles someone listens to, with their interfaces, in the world's update order (in
        which the original publishes); worked out again only when turtles or listeners change."""
        key = (self.world.roster, self._watched_revision)
        if self._published[0] != key:
            pairs = [(turtle, self.watched.get(turtle.name)) for turtle in self.world.turtles()]
            self._published = (key, [(turtle, interface) for turtle, interface in pairs
                                     if interface is not None])
        return self._published[1]

    def service(self, name, service_class, handler):
        """A service of this node whose callers are noted on ~service_calls."""
        return rospy.Service(name, service_class, self.service_calls.noted(name, handler))

    # --- requests ---
    def call(self, action):
        """Queue action(now), wait for the tick that applies it, and return its result.

        A TurtlesimError is logged as an ERROR and turned into a failed service call with its text.
        """
        try:
            return self.requests.call(action, rospy.is_shutdown, SHUTDOWN_POLL)
        except Stopped:
            raise rospy.ServiceException('turtlesim is shutting down') from None
        except TurtlesimError as error:
            rospy.logerr(str(error))
            raise rospy.ServiceException(str(error)) from None

    def on_cmd_vel(self, twist, name):
        values = (twist.linear.x, twist.linear.y, twist.angular.z)
        if self.record:
            sender = sim_record_ros.sender_of(twist)
            self.note('command', turtle=name, linear=values[0], angular=values[2], sender=sender['label'],
                      nodes=sender['nodes'])
        self.requests.submit(lambda now: self.world.command_velocity(name, *values, now))
        self.ticks.commanded()

    def set_pen(self, name, req):
        def apply(now):
            self.world.set_pen(name, req.r, req.g, req.b, req.width, req.off)
            self.drawn('pen', now, turtle=name, r=req.r, g=req.g, b=req.b, width=req.width, off=bool(req.off))
        self.call(apply)
        return SetPenResponse()

    def teleport_absolute(self, name, req):
        self.call(lambda now: self.world.teleport_absolute(name, req.x, req.y, req.theta))
        return TeleportAbsoluteResponse()

    def teleport_relative(self, name, req):
        self.call(lambda now: self.world.teleport_relative(name, req.linear, req.angular))
        return TeleportRelativeResponse()

    def clear(self, _req):
        background = self.read_background()
        def apply(now):
            self.world.clear(background)
            self.drawn('clear', now, background=list(background))
        self.call(apply)
        return EmptyResponse()

    def reset(self, _req):
        background = self.read_background()
        with self._registry_lock:
            def apply(now):
                self.world.reset(background)
                self.drawn('clear', now, background=list(background))
            self.call(apply)
            failed = self._sync_interfaces()
        if failed:
            message = 'Cannot spawn turtle [%s]: %s' % next(iter(failed.items()))
            rospy.logerr(message)
            raise rospy.ServiceException(message)
        return EmptyResponse()

    def spawn(self, req):
        with self._registry_lock:
            refusal = spawn_refusal(req.name, open_file_count(), open_file_limit())
            if refusal is not None:
                rospy.logerr(refusal)
                raise rospy.ServiceException(refusal)
            name = self.call(lambda now: self.world.spawn(req.name, req.x, req.y, req.theta))
            failed = self._sync_interfaces()
        if name in failed:
            message = 'Cannot spawn turtle [%s]: %s' % (name, failed[name])
            rospy.logerr(message)
            raise rospy.ServiceException(message)
        return SpawnResponse(name)

    def kill(self, req):
        with self._registry_lock:
            self.call(lambda now: self.world.kill(req.name))
            self._sync_interfaces()
        return KillResponse()

    def _sync_interfaces(self):
        """Give every turtle of the world its topics and services, and remove those of the dead.

        A turtle whose topics and services cannot be made is taken out of the world again (so no
        half-made turtle stays): returns {name: error} of those."""
        with self.world_lock:
            names = [turtle.name for turtle in self.world.turtles()]
        current = self.interfaces
        updated, failed = {}, {}
        for name in names:
            if name in current:
                updated[name] = current[name]
                continue
            try:
                updated[name] = TurtleInterface(self, name)
            except Exception as error:  # e.g. OSError: no file left for the call to the master
                failed[name] = error
        self.interfaces = updated
        for name, interface in current.items():
            if name not in updated:
                interface.close()
        for name in failed:
            self._remove_from_world(name)
        return failed

    def _remove_from_world(self, name):
        """Take a turtle out of the world without a log line: undoing a spawn that failed."""
        try:
            self.requests.call(lambda now: self.world.kill(name), rospy.is_shutdown, SHUTDOWN_POLL)
        except (Stopped, TurtlesimError):
            pass

    # --- pictures ---
    def revision(self):
        """Changes whenever the picture may have changed."""
        return self.world.revision, self.world.canvas.version

    def snapshot(self):
        """What the window shows right now, as a 500x500 RGB array."""
        with self.world_lock:
            pixels = self.world.canvas.pixels.copy()
            turtles = [_IconPose(turtle) for turtle in self.world.turtles()]
        return picture.compose(pixels, turtles)


class _IconPose:
    """The part of a turtle a picture needs, copied so that drawing can happen outside the lock."""
    __slots__ = ('x', 'qt_y', 'theta', 'icon')

    def __init__(self, turtle):
        self.x, self.qt_y, self.theta, self.icon = turtle.x, turtle.qt_y, turtle.theta, turtle.icon


def _wants_window():
    if not os.environ.get('DISPLAY'):
        return False
    return rospy.get_param('~gui', True) not in (False, 'false', 'False', 0)


def _stop_on_signals():
    """An event set by Ctrl-C (SIGINT) or SIGTERM; the main thread then shuts the node down."""
    requested = threading.Event()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signal_number, lambda *_: requested.set())
    return requested


def main():
    stop = _stop_on_signals()
    try:
        node = TurtlesimNode()
    except ValueError as error:  # a parameter or an option it cannot run with
        rospy.logfatal('turtlesim: %s' % error)
        sys.exit(1)
    node.start()

    def running():
        return not (stop.is_set() or rospy.is_shutdown())
    if _wants_window():
        from turtlesim.window import run_window
        run_window(node, running, SHUTDOWN_POLL)
    else:
        while running():
            stop.wait(SHUTDOWN_POLL)
    rospy.signal_shutdown('Ctrl-C' if stop.is_set() else 'shut down')
    node.join()
    node.canvas_outputs.save_at_shutdown()
