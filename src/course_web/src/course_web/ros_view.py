"""course_web's ROS layer: turns turtlesim's ~scene, fake_tb3's odom and scan into the scenes the
page draws, and the page's keys into the teleops' commands. Nothing else reaches ROS from a page.

Threads: rospy's callbacks change the scenes (under their lock) and wake the web server; the web
server (tornado) runs in the main thread; a presence thread asks the master twice a second which
simulators run, so the page follows one that stops or restarts.
"""
import asyncio
import json
import math
import signal
import sys
import threading
import xmlrpc.client

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
import tornado.ioloop

from course_web.frames import Scenes
from course_web.protocol import TURTLESIM_KEYS
from course_web.server import ViewServer
from course_web.turtlesim_scene import SceneError
from fake_tb3.models import UnknownModelError
from fake_tb3.world import WorldError, load_world
from turtlebot3_teleop.key_commands import KeyCommands, speed_limits

PRESENCE_PERIOD = 0.5  # s between looks at which simulators run
TB3_PUBLISH_PERIOD = 0.1  # s, as turtlebot3_teleop_key


class _QuickTransport(xmlrpc.client.Transport):
    def make_connection(self, host):
        connection = super().make_connection(host)
        connection.timeout = 2.0
        return connection


def _refuse_constant(name):
    raise ValueError('%s in a ~scene message' % name)


def _twist(linear, angular):
    command = Twist()
    command.linear.x, command.angular.z = linear, angular
    return command


class RosView:
    def __init__(self, allowed_hosts):
        self.scenes = Scenes()
        self.server = ViewServer(self.scenes, self.on_key, rospy.logwarn, allowed_hosts)
        self.turtlesim_node = rospy.resolve_name(rospy.get_param('~turtlesim', '/turtlesim'))
        self.fake_tb3_node = rospy.resolve_name(rospy.get_param('~fake_tb3', '/fake_tb3'))
        # The teleops' topics and numbers: turtle_teleop_key and turtlebot3_teleop_key.
        self.scale_linear = float(rospy.get_param('scale_linear', 2.0))
        self.scale_angular = float(rospy.get_param('scale_angular', 2.0))
        self.turtle_commands = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
        self.tb3_commands = rospy.Publisher('cmd_vel', Twist, queue_size=1)
        self.tb3_keys = None  # KeyCommands, made at the first key with the running model's limits
        self.tb3_model = None
        self.tb3_lock = threading.Lock()
        self.tb3_driving = False
        self.scene_subscriber = None
        self.resubscribe = threading.Event()
        self._subscribe_scene()
        rospy.Subscriber('odom', Odometry, self.on_odom, queue_size=1)
        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1)
        self.master = rosgraph.Master(rospy.get_name())
        self._threads = [threading.Thread(target=self._watch_simulators, daemon=True),
                         threading.Thread(target=self._drive_tb3, daemon=True)]

    def start(self):
        for thread in self._threads:
            thread.start()

    # --- simulators -> scenes ---
    def _subscribe_scene(self):
        if self.scene_subscriber is not None:
            self.scene_subscriber.unregister()
        self.scene_subscriber = rospy.Subscriber(self.turtlesim_node + '/scene', String,
                                                 self.on_scene, queue_size=100)

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
        pose, twist = message.pose.pose, message.twist.twist
        yaw = 2.0 * math.atan2(pose.orientation.z, pose.orientation.w)
        with self.scenes.lock:
            self.scenes.tb3.on_odom(pose.position.x, pose.position.y, math.atan2(math.sin(yaw), math.cos(yaw)),
                                    twist.linear.x, twist.angular.z)
        self.server.notify()

    def on_scan(self, message):
        with self.scenes.lock:
            self.scenes.tb3.on_scan(message.ranges, message.angle_min, message.angle_increment,
                                    message.range_min, message.range_max)
        self.server.notify()

    def _node_uri(self, name):
        """The node's URI if it runs: registered with the master and answering there (a node
        killed without unregistering, as turtlesim by Ctrl-C, stays registered)."""
        try:
            uri = self.master.lookupNode(name)
            xmlrpc.client.ServerProxy(uri, transport=_QuickTransport()).getPid(rospy.get_name())
            return uri
        except Exception:  # unknown node, no master at the moment, or a node that is gone
            return None

    def _watch_simulators(self):
        turtlesim_uri = fake_tb3_uri = None
        while not rospy.is_shutdown():
            uri = self._node_uri(self.turtlesim_node)
            if uri != turtlesim_uri:
                turtlesim_uri = uri
                if uri is None:
                    with self.scenes.lock:
                        self.scenes.turtlesim.vanish()
                    self.server.notify()
            if self.resubscribe.is_set() and uri is not None:
                self.resubscribe.clear()
                rospy.logwarn('course_web: missed a ~scene message of turtlesim: asking for the whole picture again')
                self._subscribe_scene()
            uri = self._node_uri(self.fake_tb3_node)
            if uri != fake_tb3_uri:
                fake_tb3_uri = uri
                self._follow_fake_tb3(uri)
            rospy.rostime.wallsleep(PRESENCE_PERIOD)

    def _follow_fake_tb3(self, uri):
        world = model = None
        if uri is not None:
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
            self.turtle_commands.publish(_twist(self.scale_linear * linear, self.scale_angular * angular))
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


def main():
    rospy.init_node('course_web', disable_signals=True)  # Ctrl-C is the web loop's to handle
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
    rospy.loginfo('course_web: open http://%s:%d/ in a browser%s' % (
        shown, bound, ' (listening on every address of this machine)' if host in ('0.0.0.0', '::', '') else ''))
    loop = tornado.ioloop.IOLoop.current()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        asyncio.get_event_loop().add_signal_handler(signal_number, loop.stop)
    loop.start()
    view.server.stop()
    rospy.signal_shutdown('Ctrl-C')
