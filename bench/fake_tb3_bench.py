#!/usr/bin/env python3
"""Benchmark of fake_tb3: prints a table of the numbers it sets targets for:

  1. time per 360-beam LDS-01 scan in turtlebot3_world, and the real-time factor of the core alone
     (no ROS: one robot spinning in turtlebot3_world, the physics at 100 Hz and the scan at 5 Hz,
     as the node runs them), in CPU seconds of its thread;
  2. the highest real-time factor one robot reaches with every topic published at its simulated
     rate and a subscriber on each (/tf included), counted off the wire;
  3. how many robots (spinning on the spot, 1 m apart so that they see each other) run at 1x with
     all their topics, and the highest real-time factor 30 of them reach, with the simulator's CPU
     per simulated second (their messages are counted off the wire: rospy subscribers in this
     process would be the limit);
  4. the cost of a physics step under the most extreme finite commands (1e308 m/s, 1e308 rad/s,
     mixes, denormals; pure core), and the real-time factor and topic rates of one robot at 1x
     while such commands arrive ten times a second.

Run after building, in the ROS environment (source tools/env.sh):
    bench/fake_tb3_bench.py [--quick] [--many] [--before REV [--rounds N]] [--profile-core TOP]
--many: part 3 only. --profile-core TOP: instead, the TOP functions of the core alone by own time
(cProfile). --before REV: each figure also of fake_tb3 as it was at git revision REV
(its package and course_common's from `git archive`, first on the Python path), before and after in turn, N rounds
(default 3), medians. It starts its own roscore on a free port and stops everything it started.
"""
import argparse
import cProfile
import itertools
import json
import logging
import math
import os
import pstats
import selectors
import socket
import statistics
import struct
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client

import numpy as np
import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage

from course_common.processes import free_port, stop_process_group
from course_common.waiting import wait_until
from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import load_world

TOPIC_RATES = {'odom': (Odometry, 30), 'joint_states': (JointState, 30), 'imu': (Imu, 30),
               'scan': (LaserScan, 5)}
TF_RATE = 30  # a TFMessage per robot at each odometry tick
STAMP = struct.Struct('<II')  # secs, nsecs
LENGTH = struct.Struct('<I')
ENOUGH = 0.97  # a run keeps up when time and every topic reach this share of their due
MAX = 1.7976931348623157e308
EXTREME_COMMANDS = [(1e308, 0.0), (0.0, 1e308), (-1e308, 0.0), (0.0, -1e308), (0.0, 1e6),
                    (1e308, 1e308), (-MAX, MAX), (MAX, -1.0), (1.0, -MAX), (5e-324, 1e-310),
                    (-1e6, 1e-300)]


def scan_time(samples):
    """Mean CPU seconds per scan at random free poses inside the turtlebot3_world ring."""
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser())
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    random = np.random.default_rng(1)
    poses = []
    while len(poses) < 50:
        robot.x, robot.y = random.uniform(-2.4, 2.4, 2)
        robot.yaw = random.uniform(-math.pi, math.pi)
        if not simulation.overlapping(robot):
            poses.append(robot.pose)
    start = time.thread_time()
    for index in range(samples):
        robot.x, robot.y, robot.yaw = poses[index % len(poses)]
        simulation.scan(robot)
    return (time.thread_time() - start) / samples


def core_factor(seconds):
    """Simulated seconds per CPU second of the core alone: one robot spinning (0.5 rad/s) at the
    turtlebot3_world spawn, the physics at 100 Hz and a scan at 5 Hz, as the node runs them."""
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser())
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    simulation.command(robot, 0.0, 0.5)
    start = time.thread_time()
    for step in range(int(round(seconds * 100))):
        simulation.step(0.01)
        if step % 20 == 19:
            simulation.scans()
    return seconds / (time.thread_time() - start)


def step_times(steps_per_command):
    """(worst, mean) CPU seconds per physics step (dt 0.01) in turtlebot3_world, one robot, each
    of EXTREME_COMMANDS held for steps_per_command steps from the spawn pose, in turn. CPU time of
    this thread: what the step costs, not what other processes of a shared machine take."""
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser())
    quiet = logging.getLogger('fake_tb3_bench.collisions')  # a collision line per command
    quiet.addHandler(logging.NullHandler())
    quiet.propagate = False
    simulation = Simulation(load_world('turtlebot3_world'), [robot], log=quiet)
    times = []
    for command in EXTREME_COMMANDS:
        simulation.command(robot, *command)
        for _ in range(steps_per_command):
            start = time.thread_time()
            simulation.step(0.01)
            times.append(time.thread_time() - start)
    return max(times), sum(times) / len(times)


def start_master():
    """A roscore of our own on a free port (ROS_MASTER_URI is set to it)."""
    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    core = subprocess.Popen(['roscore', '-p', str(port)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    wait_until(rosgraph.is_master_online, 30, 'roscore', poll=0.2)
    return core


class RawSubscriber:
    """Subscribers that count messages straight off their TCPROS connections, in one thread,
    reading only each message's stamp: this process must not be the limit of what it measures (a
    rospy subscriber that deserialises every message keeps up with about 10 000 messages a second
    in Python; one robot at 100x sends 22 500). on_message(key, payload) hears every message."""

    def __init__(self, topics, on_message, caller_id='/fake_tb3_bench_raw'):
        """topics: {key: topic name}; each must have its publisher already."""
        self._selector = selectors.DefaultSelector()
        self._on_message = on_message
        self._stop = False
        master = rosgraph.Master(caller_id)
        publishers = dict((topic, nodes) for topic, nodes in master.getSystemState()[0])
        for key, topic in topics.items():
            for node in publishers.get(topic, []):
                uri = master.lookupNode(node)
                _, _, (_, host, port) = xmlrpc.client.ServerProxy(uri).requestTopic(
                    caller_id, topic, [['TCPROS']])
                connection = socket.create_connection((host, port))
                fields = [b'callerid=' + caller_id.encode(), b'topic=' + topic.encode(),
                          b'md5sum=*', b'type=*', b'tcp_nodelay=1']
                header = b''.join(struct.pack('<I', len(field)) + field for field in fields)
                connection.sendall(struct.pack('<I', len(header)) + header)
                self._selector.register(connection, selectors.EVENT_READ, [key, b'', None])
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop:
            for selected, _ in self._selector.select(0.1):
                state = selected.data
                data = selected.fileobj.recv(1 << 20)
                if not data:
                    self._selector.unregister(selected.fileobj)
                    continue
                buffer, offset = state[1] + data, 0
                while len(buffer) - offset >= 4:
                    size = LENGTH.unpack_from(buffer, offset)[0]
                    if len(buffer) - offset - 4 < size:
                        break
                    if state[2] is None:  # the publisher's connection header comes first
                        state[2] = True
                    else:
                        self._on_message(state[0], buffer, offset + 4)
                    offset += 4 + size
                state[1] = buffer[offset:]

    def close(self):
        self._stop = True
        self._thread.join()
        for key in list(self._selector.get_map().values()):
            key.fileobj.close()


class TopicCounter:
    """Counts the messages of every robot's topics stamped in [start, end), and /clock arrivals.

    raw: counted off the wire by a RawSubscriber (after the simulator is up: start() then);
    else by rospy subscribers that deserialise every message (the limit is then this process)."""

    def __init__(self, robots, raw=False):
        self.start = self.end = rospy.Time(1e9)
        self.counts = {}
        self.clock = []
        self.raw = raw
        self.topics = {'/clock': '/clock', '/tf': '/tf'}
        self.tf_rate = TF_RATE * len(robots)
        for robot in robots:
            for topic in TOPIC_RATES:
                self.topics[(robot['name'], topic)] = '/%s/%s' % (robot['name'], topic)
        self.subscribers = []
        self.raw_subscriber = None
        if not raw:
            self.subscribers.append(rospy.Subscriber('/clock', Clock, self._on_clock))
            self.subscribers.append(rospy.Subscriber('/tf', TFMessage, self._on_tf))
            for key, topic in self.topics.items():
                if key not in ('/clock', '/tf'):
                    self.subscribers.append(rospy.Subscriber(
                        topic, TOPIC_RATES[key[1]][0], self._counter(key)))

    def connect(self):
        """The raw subscribers, once every topic has its publisher."""
        if self.raw and self.raw_subscriber is None:
            self.raw_subscriber = RawSubscriber(self.topics, self._raw_message)

    def _raw_message(self, key, buffer, offset):
        if key == '/clock':
            self.clock.append((time.monotonic(), rospy.Time(*STAMP.unpack_from(buffer, offset))))
            return
        # After the header's seq (and for /tf, the transforms' count before it).
        stamp = rospy.Time(*STAMP.unpack_from(buffer, offset + (8 if key == '/tf' else 4)))
        if self.start <= stamp < self.end:
            self.counts[key] = self.counts.get(key, 0) + 1

    def _on_tf(self, message):
        if self.start <= message.transforms[0].header.stamp < self.end:
            self.counts['/tf'] = self.counts.get('/tf', 0) + 1

    def _on_clock(self, message):
        self.clock.append((time.monotonic(), message.clock))

    def _counter(self, key):
        def count(message):
            if self.start <= message.header.stamp < self.end:
                self.counts[key] = self.counts.get(key, 0) + 1
        return count

    def close(self):
        for subscriber in self.subscribers:
            subscriber.unregister()
        if self.raw_subscriber is not None:
            self.raw_subscriber.close()


def run_simulator(name, real_time_factor, robots, seconds, commands=((0.0, 0.5),), raw=False,
                  python_path=None):
    """Run fake_tb3 with `robots` (spawn dicts) at real_time_factor, every robot driven by
    `commands` (linear, angular) in turn, ten a second (one command: sent once), and measure for
    `seconds` of wall time. python_path: folders put first on the simulator's Python path (an
    older fake_tb3 package: older_package).

    Returns (achieved real-time factor, the lowest share of its due messages any topic got, CPU
    seconds the simulator used per simulated second: what the load of a shared machine does not
    change)."""
    rospy.set_param('/use_sim_time', True)
    rospy.set_param('/%s/world' % name, 'turtlebot3_world' if len(robots) == 1 else 'empty')
    rospy.set_param('/%s/real_time_factor' % name, real_time_factor)
    rospy.set_param('/%s/robots' % name, robots)
    simulator = subprocess.Popen(['rosrun', 'fake_tb3', 'fake_tb3_node', '__name:=' + name],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                 start_new_session=True, env=_environment(python_path))
    counter = TopicCounter(robots, raw)
    cmd_vels = [rospy.Publisher('/%s/cmd_vel' % robot['name'], Twist, queue_size=1, latch=True)
                for robot in robots]
    try:
        # The simulator subscribes to cmd_vel after it has made all its publishers.
        wait_until(lambda: simulator.poll() is not None
                   or all(p.get_num_connections() for p in cmd_vels),
                   60, 'the simulator to start', poll=0.1)
        if simulator.poll() is not None:
            raise RuntimeError('the simulator exited (code %d)' % simulator.returncode)
        counter.connect()
        wait_until(lambda: len(counter.clock) >= 10, 30, '/clock', poll=0.1)
        stop = threading.Event()

        def drive():
            for linear, angular in itertools.cycle(commands):
                twist = Twist()
                twist.linear.x, twist.angular.z = linear, angular
                for publisher in cmd_vels:
                    publisher.publish(twist)
                if len(commands) == 1 or stop.wait(0.1):
                    return

        driver = threading.Thread(target=drive, daemon=True)
        driver.start()
        time.sleep(1.0)  # every subscriber connected and running
        first_wall, first_clock = counter.clock[-1]
        first_cpu = _cpu_seconds(simulator.pid)
        counter.start = first_clock
        time.sleep(seconds)
        last_wall, last_clock = counter.clock[-1]
        last_cpu = _cpu_seconds(simulator.pid)
        counter.end = last_clock
        time.sleep(0.5)  # what was stamped before the window's end and is still on its way
        stop.set()
        driver.join()
        simulated = (last_clock - first_clock).to_sec()
        lowest = min([counter.counts.get((robot['name'], topic), 0) / (rate * simulated)
                      for robot in robots for topic, (_, rate) in TOPIC_RATES.items()]
                     + [counter.counts.get('/tf', 0) / (counter.tf_rate * simulated)])
        return simulated / (last_wall - first_wall), lowest, (last_cpu - first_cpu) / simulated
    finally:
        counter.close()
        for publisher in cmd_vels:
            publisher.unregister()
        stop_process_group(simulator, 30)


def _cpu_seconds(pid):
    """User and system CPU seconds process pid has used (its threads included)."""
    with open('/proc/%d/stat' % pid) as stat:
        fields = stat.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def grid_of_robots(count):
    """Robots 1 m apart on a grid, so that each one's laser sees its neighbours."""
    side = math.ceil(math.sqrt(count))
    return [{'name': 'tb3_%d' % index, 'model': 'burger', 'x_pos': float(index % side),
             'y_pos': float(index // side), 'yaw': 0.0} for index in range(count)]


def _environment(python_path):
    """This process's environment, with python_path (if any: folders joined by os.pathsep) first on the Python path."""
    environment = dict(os.environ)
    if python_path:
        environment['PYTHONPATH'] = os.pathsep.join(
            [python_path] + [part for part in [os.environ.get('PYTHONPATH')] if part])
    return environment


def core_figures(quick, python_path=None):
    """The pure core's figures (part 1 and the step costs of part 4) of the fake_tb3 package first
    on python_path, measured in a process of their own: {'scan': s per scan, 'core': real-time
    factor of the core alone, 'worst' and 'mean': CPU s per physics step, extreme commands}."""
    output = subprocess.run([sys.executable, os.path.abspath(__file__), '--core-json']
                            + (['--quick'] if quick else []), env=_environment(python_path),
                            check=True, stdout=subprocess.PIPE, universal_newlines=True).stdout
    return json.loads(output)


def _core_json(quick):
    """What core_figures() reads, measured in this process."""
    worst, mean = step_times(30 if quick else 100)
    return {'scan': scan_time(500 if quick else 3000), 'core': core_factor(20 if quick else 60),
            'worst': worst, 'mean': mean}


def core_profile(quick, top, python_path=None):
    """The `top` functions of the core alone (core_factor under cProfile, CPU time of its thread)
    by own time, of the fake_tb3 package first on python_path, in a process of their own:
    [(function, own ms per simulated second, calls per simulated second)]."""
    output = subprocess.run([sys.executable, os.path.abspath(__file__), '--core-profile-json',
                             str(top)] + (['--quick'] if quick else []),
                            env=_environment(python_path), check=True, stdout=subprocess.PIPE,
                            universal_newlines=True).stdout
    return json.loads(output)


def _core_profile_json(quick, top):
    """What core_profile() reads, measured in this process."""
    seconds = 20 if quick else 60
    profile = cProfile.Profile(time.thread_time)
    profile.runcall(core_factor, seconds)
    entries = sorted(pstats.Stats(profile).stats.items(), key=lambda entry: -entry[1][2])[:top]
    return [('%s (%s:%d)' % (name, '/'.join(path.split('/')[-2:]), line),
             1e3 * own / seconds, calls / seconds)
            for (path, line, name), (_, calls, own, _, _) in entries]


def older_package(revision, folder):
    """fake_tb3's Python package as it was at git `revision`, and course_common's (its ROS layer's
    batched writes and clock), unpacked under folder: what to put first on the Python path (the
    worlds beside fake_tb3's, where it looks for them)."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    archive = subprocess.run(['git', 'archive', revision, 'src/fake_tb3', 'src/course_common'], cwd=root, check=True,
                             stdout=subprocess.PIPE).stdout
    subprocess.run(['tar', '-x', '-C', folder], input=archive, check=True)
    return os.pathsep.join(os.path.join(folder, 'src', package, 'src') for package in ('fake_tb3', 'course_common'))


SPAWN = {'name': 'tb3_0', 'model': 'burger', 'x_pos': -2.0, 'y_pos': -0.5, 'yaw': 0.0}
# Asked of the simulator when it runs as fast as it can: far beyond what it reaches.
FLAT_OUT = 100000.0


def measure_round(seconds, quick, many_only, python_path):
    """One round of every figure of one fake_tb3 package: {name: number}."""
    figures = {}
    if not many_only:
        figures.update(core_figures(quick, python_path))
        figures['one'], figures['one_topics'], figures['one_cpu'] = run_simulator(
            'bench_one', FLAT_OUT, [SPAWN], seconds, raw=True, python_path=python_path)
        figures['extreme'], figures['extreme_topics'], _ = run_simulator(
            'bench_extreme', 1.0, [SPAWN], seconds, EXTREME_COMMANDS, python_path=python_path)
    figures['thirty'], figures['thirty_topics'], figures['thirty_cpu'] = run_simulator(
        'bench_30_fast', FLAT_OUT, grid_of_robots(30), seconds, raw=True, python_path=python_path)
    return figures


def rows_of(figures, many_only):
    """(measure, value text, target, met) of each figure."""
    rows = []
    if not many_only:
        rows += [
            ('time per 360-beam scan, turtlebot3_world (CPU)', '%.3f ms' % (figures['scan'] * 1e3),
             '<= 0.2 ms', figures['scan'] <= 0.2e-3),
            ('core alone, 1 robot, physics 100 Hz + scan 5 Hz (CPU)', '%.0fx' % figures['core'],
             '>= 1000x', figures['core'] >= 1000),
            # A physics step must fit in its 10 ms period at 1x, whatever the command.
            ('CPU per physics step, extreme commands, turtlebot3_world',
             'worst %.2f ms, mean %.2f ms' % (figures['worst'] * 1e3, figures['mean'] * 1e3),
             '<= 10 ms', figures['worst'] <= 10e-3),
            ('highest real-time factor, 1 robot, all topics',
             '%.1fx (topics at >= %.0f%%; CPU %.4f s a simulated s)'
             % (figures['one'], 100 * figures['one_topics'], figures['one_cpu']),
             '>= 300x', figures['one'] >= 300 and figures['one_topics'] >= ENOUGH),
            ('1 robot at 1x under extreme commands (10/s)',
             '%.3fx (topics at >= %.1f%%)' % (figures['extreme'], 100 * figures['extreme_topics']),
             '1x, 100%', figures['extreme'] >= ENOUGH and figures['extreme_topics'] >= ENOUGH)]
    rows.append(('highest real-time factor, 30 robots, all topics',
                 '%.1fx (topics at >= %.0f%%; CPU %.3f s a simulated s)'
                 % (figures['thirty'], 100 * figures['thirty_topics'], figures['thirty_cpu']),
                 '>= 20x', figures['thirty'] >= 20 and figures['thirty_topics'] >= ENOUGH))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--quick', action='store_true', help='shorter measurements')
    parser.add_argument('--many', action='store_true', help='only the measures of many robots')
    parser.add_argument('--before', metavar='REV',
                        help='also measure fake_tb3 as it was at this git revision')
    parser.add_argument('--rounds', type=int, default=3,
                        help='with --before: rounds of before and after in turn (medians)')
    parser.add_argument('--profile-core', type=int, metavar='TOP',
                        help='instead: the TOP functions of the core alone by own time '
                             '(cProfile), of each package')
    parser.add_argument('--core-json', action='store_true', help=argparse.SUPPRESS)
    parser.add_argument('--core-profile-json', type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.core_json:
        print(json.dumps(_core_json(args.quick)))
        return
    if args.core_profile_json:
        print(json.dumps(_core_profile_json(args.quick, args.core_profile_json)))
        return
    seconds = 3.0 if args.quick else 8.0
    with tempfile.TemporaryDirectory(prefix='fake_tb3_before_') as folder:
        packages = [('today', None)]
        if args.before:
            packages.insert(0, (args.before, older_package(args.before, folder)))
        if args.profile_core:
            for name, python_path in packages:
                print('%s: own ms (CPU) per simulated second, calls per simulated second' % name)
                for function, own, calls in core_profile(args.quick, args.profile_core,
                                                         python_path):
                    print('| %s | %.3f | %.0f |' % (function, own, calls))
            return
        rounds = {name: [] for name, _ in packages}
        core = start_master()
        try:
            rospy.init_node('fake_tb3_bench', disable_signals=True)
            for _ in range(args.rounds if args.before else 1):
                for name, python_path in packages:
                    rounds[name].append(measure_round(seconds, args.quick, args.many,
                                                      python_path))
            most = robots_at_1x(seconds)
        finally:
            stop_process_group(core, 30)
    columns = [(name, rows_of({key: statistics.median(figures[key] for figures in measured)
                               for key in measured[0]}, args.many))
               for name, measured in rounds.items()]
    rows = [(measure, [column[index][1] for _, column in columns], target, met)
            for index, (measure, _, target, met) in enumerate(columns[-1][1])]
    rows.append(('robots at 1x with all topics (today)',
                 ['-'] * (len(columns) - 1)
                 + ['%d%s' % (most, ' (the most tried)' if most == ROBOTS_TRIED[-1] else '')],
                 '>= 10', most >= 10))
    if args.before:
        print('medians of %d rounds, before (%s) and today in turn; load average %s'
              % (args.rounds, args.before, ' '.join('%.1f' % load for load in os.getloadavg())))
    width = max(len(row[0]) for row in rows)
    value_width = max(len(value) for row in rows for value in row[1])
    print('| %-*s | %s | %-9s | met |' % (width, 'measure', ' | '.join(
        '%-*s' % (value_width, name) for name, _ in columns), 'target'))
    print('|%s|%s|%s|-----|' % ('-' * (width + 2), '|'.join(
        '-' * (value_width + 2) for _ in columns), '-' * 11))
    for measure, values, target, met in rows:
        print('| %-*s | %s | %-9s | %-3s |' % (width, measure, ' | '.join(
            '%-*s' % (value_width, value) for value in values), target, 'yes' if met else 'NO'))


ROBOTS_TRIED = (10, 20, 30, 40, 60, 80, 100, 120, 150, 200)


def robots_at_1x(seconds):
    """The most robots (of ROBOTS_TRIED) that run at 1x with all their topics, today's fake_tb3."""
    most = 0
    for count in ROBOTS_TRIED:
        factor, lowest, _ = run_simulator('bench_%d' % count, 1.0, grid_of_robots(count), seconds,
                                          raw=True)
        print('%2d robots at 1x: real-time factor %.3f, topics at >= %.1f%% of their rate'
              % (count, factor, 100 * lowest), file=sys.stderr, flush=True)
        if factor < ENOUGH or lowest < ENOUGH:
            break
        most = count
    return most


if __name__ == '__main__':
    main()
