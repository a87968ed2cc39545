"""course_web's ROS layer: turns turtlesim's ~scene, fake_tb3's odom and scan into the scenes the
page draws, and the page's keys into the teleops' commands. Nothing else reaches ROS from a page.

It listens to the simulators only while a page is connected (and a few seconds after the last one
left), so a view nobody watches costs them nothing. Threads: rospy's callbacks change the scenes
(under their lock) and wake the web server, which sends one frame per turtlesim tick (the
TurtleBot3's updates ride along, or go within a tick); the web server (tornado) runs in the main
thread; a watch thread, while pages are connected, sees from the subscriptions' connections whether
a simulator is still there and asks the master every few seconds which node is turtlesim (whatever
its name: the node that publishes its own ~scene) and whether fake_tb3 runs.
"""
import asyncio
import json
import re
import signal
import sys
import threading
import time

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
import tornado.ioloop

from course_common.sim_clock import stop_hearing_clock
from course_web.frames import Scenes
from course_web.protocol import TURTLESIM_KEYS
from course_web.server import ViewServer
from course_web.tb3_scene import odometry_fields
from course_web.turtlesim_scene import SceneError
from fake_tb3.models import UnknownModelError
from fake_tb3.world import WorldError, load_world
from turtlebot3_teleop.key_commands import KeyCommands, speed_limits
from turtlesim.world import TICK_SECONDS

CONNECTION_PERIOD = 0.5  # s between looks at the subscriptions' connections
MASTER_PERIOD = 2.0  # s between questions to the master
IDLE_SECONDS = 3.0  # s after the last page left before the simulators are let go
TB3_FRAME_WITHIN = TICK_SECONDS  # s: a TurtleBot3 update waits at most this for turtlesim's next tick
TB3_PUBLISH_PERIOD = 0.1  # s, as turtlebot3_teleop_key
RELAY_TOPIC = 'cmd_vel_mux/input/teleop'  # the 000 lab's relay listens here, as turtlebot_teleop publishes


def _refuse_constant(name):
    raise ValueError('%s in a ~scene message' % name)


def _twist(linear, angular):
    command = Twist()
    command.linear.x, command.angular.z = linear, angular
    return command


def turtlesim_nodes(publishers):
    """The nodes that publish their own ~scene (turtlesim's way), from the master's
    [[topic, [node, ...]], ...]."""
    return sorted(node for topic, nodes in publishers for node in nodes if topic == node + '/scene')


class RosView:
    def __init__(self, allowed_hosts):
        self.scenes = Scenes()
        self.server = ViewServer(self.scenes, self.on_key, rospy.logwarn, allowed_hosts, self.on_pages)
        self.fake_tb3_node = rospy.resolve_name(rospy.get_param('~fake_tb3', '/fake_tb3'))
        # The teleops' topics and numbers: turtle_teleop_key and turtlebot3_teleop_key.
        self.scale_linear = float(rospy.get_param('scale_linear', 2.0))
        self.scale_angular = float(rospy.get_param('scale_angular', 2.0))
        self.turtle_commands = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
        self.relay_commands = rospy.Publisher(RELAY_TOPIC, Twist, queue_size=1)
        self.tb3_commands = rospy.Publisher('cmd_vel', Twist, queue_size=1)
        self.tb3_keys = None  # KeyCommands, made at the first key with the running model's limits
        self.tb3_model = None
        self.tb3_lock = threading.Lock()
        self.tb3_driving = False
        self.page_count = 0
        self.pages_changed = threading.Event()
        self.resubscribe = threading.Event()
        self.subscribers = None  # {'scene', 'odom', 'scan'} while listening
        self.turtlesim_node = None
        self.turtlesim_shown = False
        self.fake_tb3_listed = False
        self.fake_tb3_shown = False
        self.master = rosgraph.Master(rospy.get_name())
        self._threads = [threading.Thread(target=self._watch, daemon=True),
                         threading.Thread(target=self._drive_tb3, daemon=True)]

    def start(self):
        for thread in self._threads:
            thread.start()

    def on_pages(self, count):
        """In the web thread: `count` pages are connected now."""
        self.page_count = count
        self.pages_changed.set()

    # --- simulators -> scenes ---
    def _watch(self):
        next_master_look, idle_since = 0.0, None
        while not rospy.is_shutdown():
            now = time.monotonic()
            if self.page_count:
                idle_since = None
                if self.subscribers is None:
                    self._listen()
                    next_master_look = 0.0
                if now >= next_master_look:
                    self._look_at_master()
                    next_master_look = now + MASTER_PERIOD
                self._look_at_connections()
            elif self.subscribers is not None:
                idle_since = idle_since or now
                if now - idle_since >= IDLE_SECONDS:
                    self._let_go()
            self.pages_changed.wait(CONNECTION_PERIOD if self.subscribers is not None else 1.0)
            self.pages_changed.clear()

    def _listen(self):
        self.subscribers = {'odom': rospy.Subscriber('odom', Odometry, self.on_odom, queue_size=1),
                            'scan': rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1),
                            'scene': None}
        if self.turtlesim_node is not None:
            self._subscribe_scene()

    def _let_go(self):
        for subscriber in self.subscribers.values():
            if subscriber is not None:
                subscriber.unregister()
        self.subscribers = None
        self.turtlesim_shown = self.fake_tb3_shown = False
        with self.scenes.lock:
            self.scenes.turtlesim.vanish()
            self.scenes.tb3.vanish()

    def _subscribe_scene(self):
        if self.subscribers['scene'] is not None:
            self.subscribers['scene'].unregister()
        self.subscribers['scene'] = rospy.Subscriber(self.turtlesim_node + '/scene', String,
                                                     self.on_scene, queue_size=100)

    def _look_at_master(self):
        """Which node is turtlesim, and whether fake_tb3 runs (one question to the master). While
        turtlesim is connected and fake_tb3 is listed (or has no node), a look at fake_tb3's node
        alone is enough: the whole state of a master with 100 turtles is a large answer to parse."""
        if self.turtlesim_shown:
            try:
                self.master.lookupNode(self.fake_tb3_node)
                fake_tb3_up = True
            except rosgraph.MasterError:
                fake_tb3_up = False
            except Exception:  # no master at the moment: the connections tell what is gone
                return
            if not fake_tb3_up or self.fake_tb3_listed:
                self.fake_tb3_listed = fake_tb3_up
                return
        try:
            publishers = self.master.getSystemState()[0]
        except Exception:  # no master at the moment: the connections tell what is gone
            return
        found = turtlesim_nodes(publishers)
        if found and self.turtlesim_node not in found:
            self.turtlesim_node = found[0]
            self._subscribe_scene()
        odom = rospy.resolve_name('odom')
        self.fake_tb3_listed = any(topic == odom and self.fake_tb3_node in nodes for topic, nodes in publishers)

    def _look_at_connections(self):
        scene = self.subscribers['scene']
        connected = scene is not None and scene.get_num_connections() > 0
        if self.resubscribe.is_set() and connected:
            self.resubscribe.clear()
            rospy.logwarn('course_web: missed a ~scene message of turtlesim: asking for the whole picture again')
            self._subscribe_scene()
            connected = False  # until the new subscription connects
        elif self.turtlesim_shown and not connected:
            with self.scenes.lock:
                self.scenes.turtlesim.vanish()
            self.server.notify()
        self.turtlesim_shown = connected
        running = self.fake_tb3_listed and self.subscribers['odom'].get_num_connections() > 0
        if running != self.fake_tb3_shown:
            self.fake_tb3_shown = running
            self._follow_fake_tb3(running)

    def on_scene(self, message):
        try:
            data = json.loads(message.data, parse_constant=_refuse_constant)
            with self.scenes.lock:
                complete = self.scenes.turtlesim.apply(data)
        except (ValueError, SceneError) as error:
            rospy.logwarn_throttle(5.0, 'course_web: %s' % error)
            return
        if not complete:
            self.resubscribe.set()  # a message was missed: a new subscription brings a new picture
        self.server.notify()

    def on_odom(self, message):
        with self.scenes.lock:
            self.scenes.tb3.on_odom(*odometry_fields(message))
        self.server.notify(TB3_FRAME_WITHIN)

    def on_scan(self, message):
        with self.scenes.lock:
            self.scenes.tb3.on_scan(message.ranges, message.angle_min, message.angle_increment,
                                    message.range_min, message.range_max)
        self.server.notify(TB3_FRAME_WITHIN)

    def _follow_fake_tb3(self, running):
        world = model = None
        if running:
            try:
                world = load_world(rospy.get_param(self.fake_tb3_node + '/world', 'empty'))
                model = rospy.get_param(self.fake_tb3_node + '/model', 'burger')
                with self.scenes.lock:
                    self.scenes.tb3.start(world, model)
            except (WorldError, UnknownModelError, KeyError, rospy.ROSException) as error:
                rospy.logwarn('course_web: cannot show fake_tb3: %s' % error)
                world = None
        if world is None:
            with self.scenes.lock:
                self.scenes.tb3.vanish()
        with self.tb3_lock:
            self.tb3_model, self.tb3_keys, self.tb3_driving = model, None, False
        self.server.notify()

    # --- the page's keys -> the teleops' commands ---
    def on_key(self, key):
        if key in TURTLESIM_KEYS:
            linear, angular = TURTLESIM_KEYS[key]
            # The 000 lab's relay (my_turtle_node) drives turtle1 from what turtlebot_teleop sends it.
            relay = self.relay_commands.get_num_connections() > 0
            (self.relay_commands if relay else self.turtle_commands).publish(
                _twist(self.scale_linear * linear, self.scale_angular * angular))
            return
        with self.tb3_lock:
            if self.tb3_keys is None:
                max_linear, max_angular, _ = speed_limits(self.tb3_model)
                self.tb3_keys = KeyCommands(max_linear, max_angular)
            self.tb3_keys.press(key)
            self.tb3_driving = True

    def _drive_tb3(self):
        """As turtlebot3_teleop_key: every 0.1 s the command ramps toward the keys' target. Only
        while the page drives (from its first key until the robot was sent a stop), so that the
        page does not fight a node that drives the robot."""
        while not rospy.is_shutdown():
            with self.tb3_lock:
                command = None
                if self.tb3_driving and self.tb3_keys is not None:
                    command = self.tb3_keys.ramp()
                    if command == (0.0, 0.0) and self.tb3_keys.target_linear == 0.0 \
                            and self.tb3_keys.target_angular == 0.0:
                        self.tb3_driving = False  # this stop is the last command sent
            if command is not None:
                self.tb3_commands.publish(_twist(*command))
            rospy.rostime.wallsleep(TB3_PUBLISH_PERIOD)


# The view's line that says where its page is (with port 0, the port the system chose).
SERVING = 'course_web: open http://%s:%d/ in a browser%s'


def served_port(output):
    """The port of the SERVING line in the view's output, None until it has said it."""
    found = re.search(r'course_web: open http://[^/\s]+:(\d+)/ in a browser', output)
    return int(found.group(1)) if found else None


def main():
    rospy.init_node('course_web', disable_signals=True)  # Ctrl-C is the web loop's to handle
    if stop_hearing_clock():  # beside a simulator on simulated time: the view needs no ROS time
        rospy.rostime.switch_to_wallclock()
    port = rospy.get_param('~port', 8080)
    host = str(rospy.get_param('~host', '127.0.0.1'))
    allowed = rospy.get_param('~allowed_hosts', '')
    allowed_hosts = [name.strip().lower() for name in str(allowed).split(',') if name.strip()]
    view = RosView(allowed_hosts)
    try:
        bound = view.server.listen(int(port), host)
    except (OSError, ValueError) as error:
        rospy.logfatal('course_web: cannot listen on %s port %s: %s' % (host, port, error))
        rospy.signal_shutdown('cannot listen')
        sys.exit(1)
    view.start()
    shown = 'localhost' if host in ('0.0.0.0', '::', '127.0.0.1', '') else host
    rospy.loginfo(SERVING % (shown, bound, ' (listening on every address of this machine)'
                             if host in ('0.0.0.0', '::', '') else ''))
    loop = tornado.ioloop.IOLoop.current()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        asyncio.get_event_loop().add_signal_handler(signal_number, loop.stop)
    loop.start()
    view.server.stop()
    rospy.signal_shutdown('Ctrl-C')
