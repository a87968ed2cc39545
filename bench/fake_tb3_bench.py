#!/usr/bin/env python3
"""Benchmark of fake_tb3: prints a table of the three numbers it has targets for.

  1. time per 360-beam LDS-01 scan in turtlebot3_world (pure core, no ROS);
  2. the highest real-time factor one robot reaches with every topic published at its simulated
     rate and a subscriber on each;
  3. how many robots (spinning on the spot, 1 m apart so that they see each other) run at 1x with
     all their topics.

Run after building, in the ROS environment (source tools/env.sh):
    bench/fake_tb3_bench.py [--quick]
It starts its own roscore on a free port and stops everything it started.
"""
import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np
import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan

from course_testing.processes import free_port, stop_process_group
from course_testing.waiting import wait_until
from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import load_world

TOPIC_RATES = {'odom': (Odometry, 30), 'joint_states': (JointState, 30), 'imu': (Imu, 30),
               'scan': (LaserScan, 5)}
ENOUGH = 0.97  # a run keeps up when time and every topic reach this share of their due


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


def start_master():
    """A roscore of our own on a free port (ROS_MASTER_URI is set to it)."""
    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    core = subprocess.Popen(['roscore', '-p', str(port)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    wait_until(rosgraph.is_master_online, 30, 'roscore', poll=0.2)
    return core


class TopicCounter:
    """Counts the messages of every robot's topics stamped after `start`, and /clock arrivals."""

    def __init__(self, robots):
        self.start = rospy.Time(1e9)
        self.counts = {}
        self.clock = []
        self.subscribers = [rospy.Subscriber('/clock', Clock, self._on_clock)]
        for robot in robots:
            for topic, (message_type, _) in TOPIC_RATES.items():
                key = (robot['name'], topic)
                self.subscribers.append(rospy.Subscriber(
                    '/%s/%s' % key, message_type, self._counter(key), queue_size=100))

    def _on_clock(self, message):
        self.clock.append((time.monotonic(), message.clock))

    def _counter(self, key):
        def count(message):
            if message.header.stamp >= self.start:
                self.counts[key] = self.counts.get(key, 0) + 1
        return count

    def close(self):
        for subscriber in self.subscribers:
            subscriber.unregister()


def run_simulator(name, real_time_factor, robots, seconds):
    """Run fake_tb3 with `robots` (spawn dicts) at real_time_factor, every robot spinning, and
    measure for `seconds` of wall time.

    Returns (achieved real-time factor, the lowest share of its due messages any topic got)."""
    rospy.set_param('/use_sim_time', True)
    rospy.set_param('/%s/world' % name, 'turtlebot3_world' if len(robots) == 1 else 'empty')
    rospy.set_param('/%s/real_time_factor' % name, real_time_factor)
    rospy.set_param('/%s/robots' % name, robots)
    simulator = subprocess.Popen(['rosrun', 'fake_tb3', 'fake_tb3_node', '__name:=' + name],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                 start_new_session=True)
    counter = TopicCounter(robots)
    spinners = [rospy.Publisher('/%s/cmd_vel' % robot['name'], Twist, queue_size=1, latch=True)
                for robot in robots]
    try:
        wait_until(lambda: simulator.poll() is not None or (
            len(counter.clock) >= 10 and all(p.get_num_connections() for p in spinners)),
            60, 'the simulator to start', poll=0.1)
        if simulator.poll() is not None:
            raise RuntimeError('the simulator exited (code %d)' % simulator.returncode)
        twist = Twist()
        twist.angular.z = 0.5
        for publisher in spinners:
            publisher.publish(twist)
        time.sleep(1.0)  # every subscriber connected and running
        first_wall, first_clock = counter.clock[-1]
        counter.start = first_clock
        time.sleep(seconds)
        last_wall, last_clock = counter.clock[-1]
        simulated = (last_clock - first_clock).to_sec()
        lowest = min(counter.counts.get((robot['name'], topic), 0) / (rate * simulated)
                     for robot in robots for topic, (_, rate) in TOPIC_RATES.items())
        return simulated / (last_wall - first_wall), lowest
    finally:
        counter.close()
        for publisher in spinners:
            publisher.unregister()
        stop_process_group(simulator, 30)


def grid_of_robots(count):
    """Robots 1 m apart on a grid, so that each one's laser sees its neighbours."""
    side = math.ceil(math.sqrt(count))
    return [{'name': 'tb3_%d' % index, 'model': 'burger', 'x_pos': float(index % side),
             'y_pos': float(index // side), 'yaw': 0.0} for index in range(count)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--quick', action='store_true', help='shorter measurements')
    seconds = 3.0 if parser.parse_args().quick else 8.0
    per_scan = scan_time(500 if seconds < 5 else 3000)
    rows = [('time per 360-beam scan, turtlebot3_world', '%.3f ms' % (per_scan * 1e3),
             '<= 0.2 ms', per_scan <= 0.2e-3)]
    core = start_master()
    try:
        rospy.init_node('fake_tb3_bench', disable_signals=True)
        spawn = {'name': 'tb3_0', 'model': 'burger', 'x_pos': -2.0, 'y_pos': -0.5, 'yaw': 0.0}
        factor, lowest = run_simulator('bench_one', 1000.0, [spawn], seconds)
        rows.append(('highest real-time factor, 1 robot, all topics',
                     '%.1fx (topics at >= %.0f%%)' % (factor, 100 * lowest), '>= 20x',
                     factor >= 20 and lowest >= ENOUGH))
        most, counts = 0, (10, 20, 30, 40, 50, 60, 80)
        for count in counts:
            factor, lowest = run_simulator('bench_%d' % count, 1.0, grid_of_robots(count), seconds)
            print('%2d robots at 1x: real-time factor %.3f, topics at >= %.1f%% of their rate'
                  % (count, factor, 100 * lowest), file=sys.stderr, flush=True)
            if factor < ENOUGH or lowest < ENOUGH:
                break
            most = count
        rows.append(('robots at 1x with all topics',
                     '%d%s' % (most, ' (the most tried)' if most == counts[-1] else ''), '>= 10',
                     most >= 10))
    finally:
        stop_process_group(core, 30)
    width = max(len(row[0]) for row in rows)
    print('| %-*s | %-28s | %-9s | met |' % (width, 'measure', 'value', 'target'))
    print('|%s|%s|%s|-----|' % ('-' * (width + 2), '-' * 30, '-' * 11))
    for measure, value, target, met in rows:
        print('| %-*s | %-28s | %-9s | %-3s |'
              % (width, measure, value, target, 'yes' if met else 'NO'))


if __name__ == '__main__':
    main()
