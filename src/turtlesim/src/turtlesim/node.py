"""turtlesim_node: the ROS interface of the world in turtlesim.world.

Threads: one tick thread owns the world and steps it every 16 ms. ROS callbacks (cmd_vel, service
calls) never touch the world: they queue a request that the tick thread applies between two ticks,
and a service call waits for its request to be applied and returns its result. Creating and
removing a turtle's topics and services (slow calls to the master) happens in the service thread,
so ticks stay on time. A turtle's topics and services are made all or none (a spawn that fails
half-way removes what it made, and the turtle) and a kill gives all of them back; the topics share
one epoll (turtlesim.shared_poll), so a turtle holds no open file of its own. Pictures (save_canvas,
the ~canvas topic, the window) copy the world under a lock and are drawn outside it.
"""
import collections
import os
import signal
import threading
import time

import rospkg
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import Image
from std_srvs.srv import Empty, EmptyResponse, Trigger, TriggerResponse

from turtlesim import picture, shared_poll
from turtlesim.holdings import (LOW_FILE_LIMIT, Holdings, capacity_note, open_file_count, open_file_limit,
                                raise_open_file_limit, spawn_refusal)
from turtlesim.msg import Color, Pose
from turtlesim.scene_topic import SceneTopic
from turtlesim.srv import (Kill, KillResponse, SetPen, SetPenResponse, Spawn, SpawnResponse,
                           TeleportAbsolute, TeleportAbsoluteResponse, TeleportRelative,
                           TeleportRelativeResponse)
from turtlesim.world import DEFAULT_BACKGROUND, FLOAT32_MAX, TICK_SECONDS, TurtlesimError, World

CANVAS_TOPIC_PERIOD = 1.0  # seconds between ~canvas images (only while someone subscribes)
SHUTDOWN_POLL = 0.1  # how often a waiting service call checks whether the node is shutting down


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


class _Request:
    """A change to the world, made by the tick thread; the caller may wait for its result."""
    __slots__ = ('action', 'waited', 'done', 'result', 'error')

    def __init__(self, action, waited):
        self.action = action
        self.waited = waited  # False: nobody reads the result, so an error is logged as a warning
        self.done = threading.Event()
        self.result = None
        self.error = None


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
        self.pose, self.color, _, _, _, _ = self.holdings.take_all([
            ('pose publisher', lambda: rospy.Publisher(name + '/pose', Pose, queue_size=1), _unregister),
            ('color_sensor publisher', lambda: rospy.Publisher(name + '/color_sensor', Color, queue_size=1),
             _unregister),
            ('cmd_vel subscriber',
             lambda: rospy.Subscriber(name + '/cmd_vel', Twist, node.on_cmd_vel, name, queue_size=1), _unregister),
            ('set_pen service',
             lambda: rospy.Service(name + '/set_pen', SetPen, lambda req: node.set_pen(name, req)), _shut_down),
            ('teleport_absolute service',
             lambda: rospy.Service(name + '/teleport_absolute', TeleportAbsolute,
                                   lambda req: node.teleport_absolute(name, req)), _shut_down),
            ('teleport_relative service',
             lambda: rospy.Service(name + '/teleport_relative', TeleportRelative,
                                   lambda req: node.teleport_relative(name, req)), _shut_down),
        ])

    def close(self):
        """Give everything back; what cannot be is reported, and the rest is still given back."""
        for label, error in self.holdings.release_all():
            rospy.logwarn('Turtle [%s]: could not remove its %s: %s' % (self.name, label, error))

    def publish(self, turtle):
        if self.pose.get_num_connections():
            self.pose.publish(Pose(turtle.x, turtle.y, turtle.theta, _float32(turtle.linear_velocity),
                                   _float32(turtle.wz)))
        if self.color.get_num_connections():
            self.color.publish(Color(*turtle.color))


class TurtlesimNode:
    def __init__(self):
        shared_poll.install(rospy.topics)  # before any topic exists, rosout's included
        file_limit, _ = raise_open_file_limit()
        # Ctrl-C is handled in main(): rospy's own handler could run while this thread registers
        # with the master and wait for a lock that this very thread holds.
        rospy.init_node('turtlesim', disable_signals=True)
        rospy.loginfo('Starting turtlesim with node name %s' % rospy.get_name())
        if file_limit < LOW_FILE_LIMIT:
            rospy.loginfo(capacity_note(file_limit, open_file_count() or 0))
        for channel, value in zip(('r', 'g', 'b'), DEFAULT_BACKGROUND):
            if not rospy.has_param('~background_' + channel):
                rospy.set_param('~background_' + channel, value)
        self.world = World(RosLog, self.read_background(), name_key=rospy.resolve_name)
        self.world_lock = threading.Lock()  # held while the world changes and while it is copied
        self.scene_topic = SceneTopic(self.world)  # ~scene, for a web viewer
        self._requests = collections.deque()
        self._registry_lock = threading.Lock()  # one spawn/kill/reset changes the interfaces at a time
        self.interfaces = {}  # turtle name -> TurtleInterface; replaced as a whole, never mutated
        self._sync_interfaces()
        self.canvas_png_at_shutdown = rospy.get_param('~canvas_png', '')
        self._services = [
            rospy.Service('clear', Empty, self.clear),
            rospy.Service('reset', Empty, self.reset),
            rospy.Service('spawn', Spawn, self.spawn),
            rospy.Service('kill', Kill, self.kill),
            rospy.Service('~save_canvas', Trigger, self.save_canvas),
        ]
        self.canvas_pub = rospy.Publisher('~canvas', Image, queue_size=1,
                                          subscriber_listener=_PublishOnConnect(self))
        self._canvas_timer = rospy.Timer(rospy.Duration(CANVAS_TOPIC_PERIOD), self._publish_canvas)
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
        next_tick = time.monotonic()
        while not rospy.is_shutdown():
            delay = next_tick - time.monotonic()
            if delay > 0.0:
                time.sleep(delay)
            elif delay < -TICK_SECONDS:  # fell behind (machine busy): skip the missed ticks, as a timer would
                next_tick = time.monotonic()
            with self.world_lock:
                while self._requests:
                    self._apply(self._requests.popleft(), next_tick)
                self.world.tick(next_tick)
                turtles = self.world.turtles()
            interfaces = self.interfaces
            for turtle in turtles:
                interface = interfaces.get(turtle.name)
                if interface is not None:
                    interface.publish(turtle)
            self.scene_topic.after_tick()
            next_tick += TICK_SECONDS
        self._fail_pending_requests()

    def _apply(self, request, now):
        try:
            request.result = request.action(now)
        except TurtlesimError as error:
            request.error = error
            if not request.waited:
                rospy.logwarn_throttle(1.0, str(error))
        request.done.set()

    def _fail_pending_requests(self):
        while self._requests:
            request = self._requests.popleft()
            request.error = TurtlesimError('turtlesim is shutting down')
            request.done.set()

    def join(self):
        self._tick_thread.join()

    # --- requests ---
    def submit(self, action, waited=False):
        """Queue action(now) for the tick thread and return the request."""
        request = _Request(action, waited)
        self._requests.append(request)
        return request

    def call(self, action):
        """Queue action(now), wait for the tick that applies it, and return its result.

        A TurtlesimError is logged as an ERROR and turned into a failed service call with its text.
        """
        request = self.submit(action, waited=True)
        while not request.done.wait(SHUTDOWN_POLL):
            if rospy.is_shutdown():
                raise rospy.ServiceException('turtlesim is shutting down')
        if request.error is not None:
            rospy.logerr(str(request.error))
            raise rospy.ServiceException(str(request.error))
        return request.result

    def on_cmd_vel(self, twist, name):
        values = (twist.linear.x, twist.linear.y, twist.angular.z)
        self.submit(lambda now: self.world.command_velocity(name, *values, now))

    def set_pen(self, name, req):
        self.call(lambda now: self.world.set_pen(name, req.r, req.g, req.b, req.width, req.off))
        return SetPenResponse()

    def teleport_absolute(self, name, req):
        self.call(lambda now: self.world.teleport_absolute(name, req.x, req.y, req.theta))
        return TeleportAbsoluteResponse()

    def teleport_relative(self, name, req):
        self.call(lambda now: self.world.teleport_relative(name, req.linear, req.angular))
        return TeleportRelativeResponse()

    def clear(self, _req):
        background = self.read_background()
        self.call(lambda now: self.world.clear(background))
        return EmptyResponse()

    def reset(self, _req):
        background = self.read_background()
        with self._registry_lock:
            self.call(lambda now: self.world.reset(background))
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
        request = self.submit(lambda now: self.world.kill(name), waited=True)
        while not request.done.wait(SHUTDOWN_POLL) and not rospy.is_shutdown():
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

    @staticmethod
    def canvas_path(param_value):
        """Where ~canvas_png points: relative paths start at ROS_HOME, where roslaunch runs nodes."""
        path = os.path.expanduser(str(param_value) if param_value else 'turtlesim_canvas.png')
        return os.path.normpath(os.path.join(rospkg.get_ros_home(), path))

    def write_canvas(self, path):
        directory = os.path.dirname(path)
        if directory:
            os.makedirs(directory, exist_ok=True)
        picture.save_png(self.snapshot(), path)

    def save_canvas(self, _req):
        path = self.canvas_path(rospy.get_param('~canvas_png', ''))
        try:
            self.write_canvas(path)
        except (OSError, ValueError) as error:
            message = 'Cannot save the canvas to %s: %s' % (path, error)
            rospy.logerr(message)
            return TriggerResponse(False, message)
        return TriggerResponse(True, path)

    def canvas_message(self):
        image = self.snapshot()
        message = Image()
        message.header.stamp = rospy.Time.now()
        message.header.frame_id = 'turtlesim_canvas'
        message.height, message.width = image.shape[:2]
        message.encoding = 'rgb8'
        message.step = message.width * 3
        message.data = image.tobytes()
        return message

    def _publish_canvas(self, _event):
        if self.canvas_pub.get_num_connections():
            self.canvas_pub.publish(self.canvas_message())

    def save_at_shutdown(self):
        if not self.canvas_png_at_shutdown:
            return
        path = self.canvas_path(self.canvas_png_at_shutdown)
        try:
            self.write_canvas(path)
        except (OSError, ValueError) as error:
            print('turtlesim: cannot save the canvas to %s: %s' % (path, error))
            return
        print('turtlesim: saved the canvas to %s' % path)


class _IconPose:
    """The part of a turtle a picture needs, copied so that drawing can happen outside the lock."""
    __slots__ = ('x', 'qt_y', 'theta', 'icon')

    def __init__(self, turtle):
        self.x, self.qt_y, self.theta, self.icon = turtle.x, turtle.qt_y, turtle.theta, turtle.icon


class _PublishOnConnect(rospy.SubscribeListener):
    """A new ~canvas subscriber gets a picture at once instead of waiting for the next period."""

    def __init__(self, node):
        super().__init__()
        self.node = node

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        peer_publish(self.node.canvas_message())


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
    node = TurtlesimNode()
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
    node.save_at_shutdown()
