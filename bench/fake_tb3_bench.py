#!/usr/bin/env python3
"""Benchmark of fake_tb3: prints a table of the numbers it sets targets for:

  1. time per 360-beam LDS-01 scan in turtlebot3_world (pure core, no ROS);
  2. the highest real-time factor one robot reaches with every topic published at its simulated
     rate and a subscriber on each;
  3. how many robots (spinning on the spot, 1 m apart so that they see each other) run at 1x with
     all their topics, and the highest real-time factor 30 of them reach, with the simulator's CPU
     per simulated second (their messages are counted off the wire: rospy subscribers in this
     process would be the limit);
  4. the cost of a physics step under the most extreme finite commands (1e308 m/s, 1e308 rad/s,
     mixes, denormals; pure core), and the real-time factor and topic rates of one robot at 1x
     while such commands arrive ten times a second.

Run after building, in the ROS environment (source tools/env.sh):
    bench/fake_tb3_bench.py [--quick] [--many]     (--many: part 3 only)
It starts its own roscore on a free port and stops everything it started.
"""
import argparse
import itertools
import logging
import math
import os
import selectors
import socket
import struct
import subprocess
import sys
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

from course_common.processes import free_port, stop_process_group
from course_common.waiting import wait_until
from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import load_world

TOPIC_RATES = {'odom': (Odometry, 30), 'joint_states': (JointState, 30), 'imu': (Imu, 30),
               'scan': (LaserScan, 5)}
STAMP = struct.Struct('<II')  # secs, nsecs
LENGTH = struct.Struct('<I')
ENOUGH = 0.97  # a run keeps up when time and every topic reach this share of their due
MAX = 1.7976931348623157e308
EXTREME_COMMANDS = [(1e308, 0.0), (0.0, 1e308), (-1e308, 0.0), (0.0, -1e308), (0.0, 1e6),
                    (1e308, 1e308), (-MAX, MAX), (MAX, -1.0), (1.0, -MAX), (5e-324, 1e-310),
                    (-1e6, 1e-300)]


def scan_time(samples):
    """Mean seconds per scan at random free poses inside the turtlebot3_world ring."""
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser())
    simulation = Simulation(load_world('turtlebot3_world'), [robot])
    random = np.random.default_rng(1)
    poses = []
    while len(poses) < 50:
        robot.x, robot.y = random.uniform(-2.4, 2.4, 2)
        robot.yaw = random.uniform(-math.pi, math.pi)
        if not simulation.overlapping(robot):
            poses.append(robot.pose)
    start = time.perf_counter()
    for index in range(samples):
        robot.x, robot.y, robot.yaw = poses[index % len(poses)]
        simulation.scan(robot)
    return (time.perf_counter() - start) / samples


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
        self.topics = {'/clock': '/clock'}
        for robot in robots:
            for topic in TOPIC_RATES:
                self.topics[(robot['name'], topic)] = '/%s/%s' % (robot['name'], topic)
        self.subscribers = []
        self.raw_subscriber = None
        if not raw:
            self.subscribers.append(rospy.Subscriber('/clock', Clock, self._on_clock))
            for key, topic in self.topics.items():
                if key != '/clock':
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
        stamp = rospy.Time(*STAMP.unpack_from(buffer, offset + 4))  # after the header's seq
        if self.start <= stamp < self.end:
            self.counts[key] = self.counts.get(key, 0) + 1

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


def run_simulator(name, real_time_factor, robots, seconds, commands=((0.0, 0.5),), raw=False):
    """Run fake_tb3 with `robots` (spawn dicts) at real_time_factor, every robot driven by
    `commands` (linear, angular) in turn, ten a second (one command: sent once), and measure for
    `seconds` of wall time.

    Returns (achieved real-time factor, the lowest share of its due messages any topic got, CPU
    seconds the simulator used per simulated second: what the load of a shared machine does not
    change)."""
    rospy.set_param('/use_sim_time', True)
    rospy.set_param('/%s/world' % name, 'turtlebot3_world' if len(robots) == 1 else 'empty')
    rospy.set_param('/%s/real_time_factor' % name, real_time_factor)
    rospy.set_param('/%s/robots' % name, robots)
    simulator = subprocess.Popen(['rosrun', 'fake_tb3', 'fake_tb3_node', '__name:=' + name],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                 start_new_session=True)
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
        lowest = min(counter.counts.get((robot['name'], topic), 0) / (rate * simulated)
                     for robot in robots for topic, (_, rate) in TOPIC_RATES.items())
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--quick', action='store_true', help='shorter measurements')
    parser.add_argument('--many', action='store_true', help='only the measures of many robots')
    args = parser.parse_args()
    seconds = 3.0 if args.quick else 8.0
    rows = []
    core = start_master()
    try:
        rospy.init_node('fake_tb3_bench', disable_signals=True)
        if not args.many:
            rows += one_robot(seconds)
        rows += many_robots(seconds)
    finally:
        stop_process_group(core, 30)
    width = max(len(row[0]) for row in rows)
    print('| %-*s | %-30s | %-9s | met |' % (width, 'measure', 'value', 'target'))
    print('|%s|%s|%s|-----|' % ('-' * (width + 2), '-' * 32, '-' * 11))
    for measure, value, target, met in rows:
        print('| %-*s | %-30s | %-9s | %-3s |'
              % (width, measure, value, target, 'yes' if met else 'NO'))


def one_robot(seconds):
    """The rows of parts 1, 2 and 4."""
    per_scan = scan_time(500 if seconds < 5 else 3000)
    rows = [('time per 360-beam scan, turtlebot3_world', '%.3f ms' % (per_scan * 1e3),
             '<= 0.2 ms', per_scan <= 0.2e-3)]
    worst, mean = step_times(30 if seconds < 5 else 100)
    # A physics step must fit in its 10 ms period at 1x, whatever the command.
    rows.append(('CPU per physics step, extreme commands, turtlebot3_world',
                 'worst %.2f ms, mean %.2f ms' % (worst * 1e3, mean * 1e3), '<= 10 ms',
                 worst <= 10e-3))
    spawn = {'name': 'tb3_0', 'model': 'burger', 'x_pos': -2.0, 'y_pos': -0.5, 'yaw': 0.0}
    factor, lowest, _ = run_simulator('bench_one', 1000.0, [spawn], seconds)
    rows.append(('highest real-time factor, 1 robot, all topics',
                 '%.1fx (topics at >= %.0f%%)' % (factor, 100 * lowest), '>= 100x',
                 factor >= 100 and lowest >= ENOUGH))
    factor, lowest, _ = run_simulator('bench_extreme', 1.0, [spawn], seconds, EXTREME_COMMANDS)
    rows.append(('1 robot at 1x under extreme commands (10/s)',
                 '%.3fx (topics at >= %.1f%%)' % (factor, 100 * lowest), '1x, 100%',
                 factor >= ENOUGH and lowest >= ENOUGH))
    return rows


def many_robots(seconds):
    """The rows of part 3."""
    rows = []
    most, counts = 0, (10, 20, 30, 40, 60, 80, 100, 120, 150, 200)
    for count in counts:
        factor, lowest, _ = run_simulator('bench_%d' % count, 1.0, grid_of_robots(count), seconds,
                                          raw=True)
        print('%2d robots at 1x: real-time factor %.3f, topics at >= %.1f%% of their rate'
              % (count, factor, 100 * lowest), file=sys.stderr, flush=True)
        if factor < ENOUGH or lowest < ENOUGH:
            break
        most = count
    rows.append(('robots at 1x with all topics',
                 '%d%s' % (most, ' (the most tried)' if most == counts[-1] else ''), '>= 10',
                 most >= 10))
    factor, lowest, cpu = run_simulator('bench_30_fast', 1000.0, grid_of_robots(30), seconds,
                                        raw=True)
    rows.append(('highest real-time factor, 30 robots, all topics',
                 '%.1fx (topics at >= %.0f%%; CPU %.3f s a simulated s)'
                 % (factor, 100 * lowest, cpu), '>= 5x', factor >= 5 and lowest >= ENOUGH))
    return rows


if __name__ == '__main__':
    main()
