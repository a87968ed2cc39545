"""A graded run's bag (course_grader.bags: `<run>.bag` in the grader's folder of a student) played on
this master as if the simulator ran again, for the live view (replay.launch: this, then view.launch).

`rosbag play --clock` plays the bag on simulated time. The view follows simulators by node name:
- a fake_tb3 bag is played under fake_tb3's name (`/fake_tb3` publishing `odom` and `scan`), with
  the run's world and model (the bag's /fake_tb3/run) set as fake_tb3's parameters;
- a turtlesim bag is played under a name of its own, and turtlesim's pure core (turtlesim.world)
  redraws it under turtlesim's name (the bag's /NAME/canvas): each replayed pose moves its turtle
  there with the pen the bag's /TURTLE/pen last set, so the trails are drawn as turtlesim drew
  them, and its ~scene (turtlesim.scene_topic) gives the view the canvas, as turtlesim's does.

A bag that cannot be read, or holds neither simulator's topics, is one sentence and exit status 1
(roslaunch then stops the view too: the node is required)."""
import argparse
import json
import os
import queue
import signal
import subprocess
import sys
import threading
import time

import rosbag
import rosgraph
import rospy
from rosgraph_msgs.msg import Clock
from std_msgs.msg import String
from turtlesim.msg import Pose
from turtlesim.scene_topic import SceneTopic
from turtlesim.srv import SetPenRequest
from turtlesim.world import TICK_SECONDS, TurtlesimError, World

SCENE = '--scene'         # this program's own mode: the turtlesim redrawn, as a node of its own
ADVERTISE_SECONDS = 1.0   # rosbag play's wait between advertising its topics and the first message
READY_SECONDS = 30        # for the redraw to subscribe to the bag's topics before the playback starts


class ReplayError(Exception):
    """A bag this cannot replay: one sentence."""


def read_bag(path):
    """What the bag holds, for the replay: {'kind': 'fake_tb3', 'world', 'model'} or {'kind':
    'turtlesim', 'node': turtlesim's full name, 'turtles': {pose topic: turtle name}}."""
    try:
        with rosbag.Bag(path) as bag:
            topics = bag.get_type_and_topic_info().topics
            run = next((message for _, message, _ in bag.read_messages(topics=['/fake_tb3/run'])), None)
    except (OSError, rosbag.ROSBagException, ValueError) as error:
        raise ReplayError('cannot read %s: %s' % (path, error)) from error
    types = {topic: info.msg_type for topic, info in topics.items()}
    if types.get('/odom') == 'nav_msgs/Odometry':
        fields = json.loads(run.data) if run is not None else {}
        return {'kind': 'fake_tb3', 'world': fields.get('world') or 'empty', 'model': fields.get('model') or 'burger'}
    canvases = sorted(topic[:-len('/canvas')] for topic, kind in types.items()
                      if topic.endswith('/canvas') and kind == 'std_msgs/String')
    turtles = {topic: topic[:-len('/pose')].rsplit('/', 1)[-1] for topic, kind in types.items()
               if topic.endswith('/pose') and kind == 'turtlesim/Pose'}
    if canvases and turtles:
        return {'kind': 'turtlesim', 'node': canvases[0], 'turtles': turtles}
    raise ReplayError('%s holds no run of fake_tb3 (/odom) nor of turtlesim (/NAME/canvas, /TURTLE/pose): '
                      'give a bag the grader wrote (<run>.bag in the student\'s folder)' % path)


def play_command(path, name, rate=1.0, loop=False):
    """`rosbag play` of the bag on simulated time (--clock), as the node `name`; it waits
    ADVERTISE_SECONDS after advertising its topics, so that the view and the redraw, already
    subscribed, are connected for the run's first messages (the canvas, the pen)."""
    return (['rosbag', 'play', '--clock', '--rate=%g' % rate, '--delay=%g' % ADVERTISE_SECONDS, '--quiet']
            + (['--loop'] if loop else []) + [path, '__name:=' + name])


def commands(path, bag, rate=1.0, loop=False):
    """The programs that replay `bag` (read_bag's) from `path`, as argv lists."""
    if bag['kind'] == 'fake_tb3':
        return [play_command(path, 'fake_tb3', rate, loop)]
    namespace, base = bag['node'].rsplit('/', 1)
    return [[sys.executable, '-m', 'course_web.replay', SCENE, path, '__name:=' + base, '__ns:=' + (namespace or '/')],
            play_command(path, 'replay_play', rate, loop)]


class Redraw:
    """turtlesim's world driven by a replayed run: each pose teleports its turtle there (drawing
    with its pen), each pen and canvas message as turtlesim applied it; one thread applies them
    in the order they came and publishes ~scene after each turn."""

    def __init__(self, turtles):
        self.world = World(_Quiet())
        self.world.kill('turtle1')   # the bag's own turtles come with their first pose
        self.scene = SceneTopic(self.world)
        self.pending = queue.Queue()
        self.turtles = turtles
        self.subscribers = [rospy.Subscriber(topic, Pose, self.heard, ('pose', name), queue_size=1000)
                            for topic, name in sorted(turtles.items())]
        self.subscribers += [rospy.Subscriber(topic[:-len('pose')] + 'pen', SetPenRequest, self.heard,
                                              ('pen', name), queue_size=100) for topic, name in sorted(turtles.items())]
        self.subscribers += [rospy.Subscriber('~canvas', String, self.heard, ('canvas', None), queue_size=100),
                             rospy.Subscriber('~turtles', String, self.heard, ('turtles', None), queue_size=100),
                             rospy.Subscriber('/clock', Clock, self.clock, queue_size=10)]
        self.last_clock = None
        self.pens = {}   # turtle name: its pen as the bag last set it
        self.background = self.world.canvas.pixels[0, 0].tolist()   # until the bag's canvas comes

    def clock(self, message):
        """rosbag play's clock: when it goes back (--loop), the run starts again on a new canvas."""
        now = message.clock.to_nsec()
        if self.last_clock is not None and now < self.last_clock:
            self.pending.put((None, 'restart', None))
        self.last_clock = now

    def heard(self, message, what):
        """rospy's threads: a replayed message, for the drawing thread (run)."""
        self.pending.put((message,) + what)

    def apply(self, message, kind, name):
        world = self.world
        try:
            if kind == 'pose':
                if world.turtle(name) is None:
                    world.spawn(name, message.x, message.y, message.theta)
                    if name in self.pens:   # set before its first pose came (another connection)
                        world.set_pen(name, *self.pens[name])
                else:   # drawn now, with the pen the turtle has now
                    world.teleport_absolute(name, message.x, message.y, message.theta)
                    world.tick(time.monotonic())
            elif kind == 'pen':
                self.pens[name] = (message.r, message.g, message.b, message.width, message.off)
                if world.turtle(name) is not None:
                    world.set_pen(name, *self.pens[name])
            elif kind == 'canvas':
                self.background = tuple(json.loads(message.data)['background'])
                world.clear(self.background)
            elif kind == 'restart':
                for turtle in world.turtles():
                    world.kill(turtle.name)
                self.pens.clear()
                world.clear(self.background)
            elif kind == 'turtles':
                names = set(json.loads(message.data)['names'])
                for turtle in world.turtles():
                    if turtle.name not in names:
                        world.kill(turtle.name)
        except (TurtlesimError, ValueError, KeyError, TypeError) as error:
            rospy.logwarn_throttle(5.0, 'replay: %s' % error)

    def run(self):
        while not rospy.is_shutdown():
            started = time.monotonic()
            while True:
                try:
                    item = self.pending.get_nowait()
                except queue.Empty:
                    break
                self.apply(*item)
            self.scene.after_tick()
            time.sleep(max(0.0, TICK_SECONDS - (time.monotonic() - started)))


class _Quiet:
    """turtlesim.world's log: the replay prints none of its lines again."""

    @staticmethod
    def info(text):
        pass

    @staticmethod
    def warning(text):
        rospy.logwarn(text)


def _scene(path):
    bag = read_bag(path)
    rospy.init_node('turtlesim', disable_signals=True)
    redraw = Redraw(bag['turtles'])
    signal.signal(signal.SIGINT, lambda *_: rospy.signal_shutdown('Ctrl-C'))
    signal.signal(signal.SIGTERM, lambda *_: rospy.signal_shutdown('stopped'))
    redraw.run()


def _true_or_false(text):
    if text.lower() not in ('true', 'false', '1', '0'):
        raise argparse.ArgumentTypeError('true or false, not %r' % text)
    return text.lower() in ('true', '1')


def _wait_for_subscriber(master, node, topics, stop):
    """Until the master lists `node` as a subscriber of every one of `topics` (READY_SECONDS at most)."""
    deadline = time.monotonic() + READY_SECONDS
    while time.monotonic() < deadline and not stop.is_set():
        try:
            subscribed = {topic for topic, nodes in master.getSystemState()[1] if node in nodes}
        except OSError:   # the master does not answer yet
            subscribed = set()
        if subscribed.issuperset(topics):
            return
        stop.wait(0.1)


def main(argv=None):
    argv = rospy.myargv(sys.argv[1:] if argv is None else argv)
    if argv[:1] == [SCENE]:
        return _scene(argv[1])
    parser = argparse.ArgumentParser(prog='replay', description='Plays a graded run\'s bag for the live view.')
    parser.add_argument('bag')
    parser.add_argument('--rate', type=float, default=1.0, help='times the run\'s own speed')
    parser.add_argument('--loop', type=_true_or_false, default=False, metavar='true|false',
                        help='play it again and again')
    args = parser.parse_args(argv)
    path = os.path.abspath(os.path.expanduser(args.bag))
    try:
        bag = read_bag(path)
    except ReplayError as error:
        print('replay: %s' % error, file=sys.stderr, flush=True)
        return 1
    master = rosgraph.Master('/replay')
    master.setParam('/use_sim_time', True)
    if bag['kind'] == 'fake_tb3':   # what the view reads of fake_tb3 to draw its world
        master.setParam('/fake_tb3/world', bag['world'])
        master.setParam('/fake_tb3/model', bag['model'])
    print('replay: playing %s (%s%s), Ctrl-C to stop' % (path, bag['kind'], ', again and again' if args.loop else ''),
          flush=True)
    stop = threading.Event()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signal_number, lambda *_: stop.set())
    children = []
    for command in commands(path, bag, args.rate, args.loop):
        if children and bag['kind'] == 'turtlesim':   # the redraw listens before the playback starts
            _wait_for_subscriber(master, bag['node'], sorted(bag['turtles']), stop)
        children.append(subprocess.Popen(command, stdin=subprocess.DEVNULL, start_new_session=True))
    told = False
    while not stop.wait(0.2):
        if children[-1].poll() is not None and not told:
            told = True
            print('replay: the bag has played to its end; Ctrl-C to stop', flush=True)
    for child in children:
        if child.poll() is None:
            child.send_signal(signal.SIGINT)
    for child in children:
        try:
            child.wait(10)
        except subprocess.TimeoutExpired:
            child.kill()
    return 0


if __name__ == '__main__':
    sys.exit(main())
