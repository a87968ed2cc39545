#!/usr/bin/env python3
"""turtlesim benchmark: tick rate, p99 gap between pose messages, CPU and open files of the node,
for 1/100/500/2000 turtles, under the open-file limit many desktops have (ulimit -n 1024).

Starts its own roscore on a free port and a headless turtlesim_node (its soft and hard open-file
limit set to --file-limit), spawns turtles through /spawn, listens to the last turtle's pose, and
prints a Markdown table. Run it after `source tools/env.sh`:

    python3 bench/turtlesim_bench.py [--window SECONDS] [--sizes 1 100 500 2000] [--file-limit 1024]

The CPU share is the node's user + system time (from /proc/<pid>/stat) over the measuring window,
in percent of one core. Targets: a pose every tick (turtlesim.world.TICK_SECONDS), p99 gap <= 18 ms,
CPU <= 3 %, 6 %, 35 %.

With `--before DEVEL` (the devel folder of another build of this workspace) it compares the two
builds side by side instead: each build runs two nodes under one master, one with turtle1 alone
and one with `--turtles` (default 2000), and each measuring window stops the other three nodes
(SIGSTOP), so that the windows of both builds and sizes alternate through the same minutes, in
`--rounds` rounds, each on a quiet machine and beside one busy process that the bench starts and
stops (`python3 -c 'while True: pass'`). Beside each window a bare sleep loop measures the
machine's own jitter, and the table gives the load average.
"""
import argparse
import os
import resource
import signal
import statistics
import subprocess
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy

from course_common.processes import free_port, stop_process_group
from course_testing.processes import build_environment, busy_core
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import Spawn
from turtlesim.world import TICK_SECONDS

TARGET_CPU = {1: 3.0, 100: 6.0, 500: 35.0}
TARGET_RATE = 1 / TICK_SECONDS
TARGET_P99_MS = 18.0


def cpu_seconds(pid):
    """User + system CPU time of a process so far (fields 14 and 15 of /proc/<pid>/stat)."""
    with open('/proc/%d/stat' % pid) as stat:
        fields = stat.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


class PoseTimes:
    """Arrival times of the messages on one pose topic."""

    def __init__(self, topic):
        self.times = []
        self._lock = threading.Lock()
        self.subscriber = rospy.Subscriber(topic, Pose, self._arrived, queue_size=10)

    def _arrived(self, _pose):
        with self._lock:
            self.times.append(time.monotonic())

    def between(self, start, end):
        with self._lock:
            return [arrival for arrival in self.times if start <= arrival <= end]


def sleep_loop_p99_lateness(seconds):
    """p99 of how late a bare Python loop wakes up on turtlesim's tick grid: the machine's own jitter (ms)."""
    lateness, next_tick = [], time.monotonic()
    for _ in range(int(seconds / TICK_SECONDS)):
        next_tick += TICK_SECONDS
        time.sleep(max(0.0, next_tick - time.monotonic()))
        lateness.append(time.monotonic() - next_tick)
    lateness.sort()
    return lateness[int(0.99 * (len(lateness) - 1))] * 1000.0


def open_files(pid):
    return len(os.listdir('/proc/%d/fd' % pid))


def measure(pid, topic, window):
    poses = PoseTimes(topic)
    wait_until(lambda: len(poses.between(0.0, time.monotonic())) >= 20, 20.0, 'poses on %s' % topic)
    start, cpu_start = time.monotonic(), cpu_seconds(pid)
    time.sleep(window)
    end, cpu_end = time.monotonic(), cpu_seconds(pid)
    poses.subscriber.unregister()
    arrivals = poses.between(start, end)
    gaps = sorted(later - earlier for earlier, later in zip(arrivals, arrivals[1:]))
    rate = (len(arrivals) - 1) / (arrivals[-1] - arrivals[0])
    p99 = gaps[min(len(gaps) - 1, int(round(0.99 * (len(gaps) - 1))))]
    return rate, p99 * 1000.0, gaps[-1] * 1000.0, 100.0 * (cpu_end - cpu_start) / (end - start)


def grid_position(number):
    """Where the bench spawns turtle `number`: a 20 x 20 grid, 0.45 m apart."""
    return 1.0 + (number % 20) * 0.45, 1.0 + (number // 20 % 20) * 0.45


def spawn_turtles(spawn, count):
    """Spawn turtles 2..count; returns the last one's name."""
    last = 'turtle1'
    for number in range(2, count + 1):
        last = spawn(*grid_position(number), 0.0, '').name
    return last


class SideBySide:
    """Each build's turtlesim node twice under one master, one with turtle1 alone and one with
    `turtles` turtles (in the namespace /BUILD_TURTLES), measured in alternating windows."""

    def __init__(self, builds, turtles, window, started):
        self.window = window
        self.rows = []  # (round, machine, turtles, build, load, rate, p99, max gap, CPU, sleep loop lateness)
        self.nodes = {}  # (build, turtles) -> [pid, last turtle's name]
        for build, environment in builds.items():
            for size in (1, turtles):
                started.append(subprocess.Popen(
                    ['rosrun', 'turtlesim', 'turtlesim_node', '__ns:=/%s_%d' % (build, size)], env=environment,
                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True))
                self.nodes[(build, size)] = [None, 'turtle1']
        for (build, size), node in self.nodes.items():
            rospy.wait_for_service('/%s_%d/spawn' % (build, size), 30.0)
            node_uri = rosgraph.Master('/turtlesim_bench').lookupNode('/%s_%d/turtlesim' % (build, size))
            node[0] = xmlrpc.client.ServerProxy(node_uri).getPid('/turtlesim_bench')[2]
        threads = [threading.Thread(target=self._spawn, args=(key,)) for key in self.nodes if key[1] > 1]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()

    def _spawn(self, key):
        self.nodes[key][1] = spawn_turtles(rospy.ServiceProxy('/%s_%d/spawn' % key, Spawn), key[1])

    def measure(self, round_number, build, turtles, busy):
        """One window of one node, the others stopped, maybe beside a busy process."""
        pid, last = self.nodes[(build, turtles)]
        others = [node[0] for key, node in self.nodes.items() if key != (build, turtles)]
        for other in others:
            os.kill(other, signal.SIGSTOP)
        try:
            with busy_core(busy):
                jitter = subprocess.Popen([sys.executable, os.path.abspath(__file__), '--sleep-loop',
                                           str(self.window)], stdout=subprocess.PIPE, universal_newlines=True)
                rate, p99, worst, cpu = measure(pid, '/%s_%d/%s/pose' % (build, turtles, last), self.window)
                lateness = float(jitter.communicate()[0])
        finally:
            for other in others:
                os.kill(other, signal.SIGCONT)
        row = (round_number, 'one busy process' if busy else 'quiet', turtles, build, os.getloadavg()[0],
               rate, p99, worst, cpu, lateness)
        self.rows.append(row)
        print('| %d | %s | %d | %s | %.1f | %.2f | %.1f | %.1f | %.1f | %.1f |' % row)
        sys.stdout.flush()

    def summary(self, turtles):
        """Medians over the rounds per machine, size and build; and of the p99 gap at `turtles`
        less the p99 gap with one turtle in the same round."""
        print('\nMedians over the rounds:\n\n| machine | turtles | build | tick rate (Hz) | p99 gap (ms) '
              '| p99 gap beyond 1 turtle\'s (ms) | max gap (ms) | CPU (% of a core) | sleep loop p99 late (ms) |')
        print('| --- | --: | --- | --: | --: | --: | --: | --: | --: |')
        by_key = {}
        for row in self.rows:
            by_key.setdefault(row[1:4], {})[row[0]] = row
        for (machine, size, build), rounds in by_key.items():
            one = by_key[(machine, 1, build)]
            beyond = statistics.median(row[6] - one[number][6] for number, row in rounds.items())
            medians = [statistics.median(row[index] for row in rounds.values()) for index in (5, 6, 7, 8, 9)]
            print('| %s | %d | %s | %.2f | %.1f | %s | %.1f | %.1f | %.1f |' % (
                machine, size, build, medians[0], medians[1], '%+.1f' % beyond if size > 1 else '-',
                medians[2], medians[3], medians[4]))


def side_by_side(args, env, started):
    """Windows of this build and of args.before, alternating (see the module's text)."""
    builds = {'before': build_environment(args.before), 'after': env}
    rospy.init_node('turtlesim_bench', disable_signals=True)
    bench = SideBySide(builds, args.turtles, args.window, started)
    print('| round | machine | turtles | build | load average | tick rate (Hz) | p99 gap (ms) | max gap (ms) '
          '| CPU (% of a core) | sleep loop p99 late (ms) |')
    print('| --: | --- | --: | --- | --: | --: | --: | --: | --: | --: |')
    for round_number in range(1, args.rounds + 1):
        for busy in (False, True):
            for turtles in (1, args.turtles):
                for build in builds:
                    bench.measure(round_number, build, turtles, busy)
    bench.summary(args.turtles)
    print('\nWindow %.0f s, %d cores; before: %s.' % (args.window, os.cpu_count(), args.before))


def sizes_table(args, env, started):
    """The table of sizes: one node under the open-file limit, turtles spawned up to each size."""
    hard = resource.getrlimit(resource.RLIMIT_NOFILE)[1]
    if args.file_limit and hard != resource.RLIM_INFINITY:
        args.file_limit = min(args.file_limit, hard)  # only root may raise a hard limit

    def file_limit():
        if args.file_limit:
            resource.setrlimit(resource.RLIMIT_NOFILE, (args.file_limit, args.file_limit))
    started.append(subprocess.Popen(['rosrun', 'turtlesim', 'turtlesim_node'], env=env,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                    start_new_session=True, preexec_fn=file_limit))
    rospy.init_node('turtlesim_bench', disable_signals=True)
    rospy.wait_for_service('/spawn', 30.0)
    node_uri = rosgraph.Master('/turtlesim_bench').lookupNode('/turtlesim')
    pid = xmlrpc.client.ServerProxy(node_uri).getPid('/turtlesim_bench')[2]
    spawn = rospy.ServiceProxy('/spawn', Spawn)

    files_at_start = open_files(pid)
    print('| turtles | tick rate (Hz) | p99 gap (ms) | max gap (ms) | CPU (% of a core) | CPU target '
          '| open files | spawn time (ms) |')
    print('|--------:|---------------:|-------------:|-------------:|------------------:|-----------:'
          '|-----------:|----------------:|')
    count, last = 1, 'turtle1'
    for size in sorted(args.sizes):
        spawned, spawn_start = 0, time.monotonic()
        while count < size:
            count += 1
            spawned += 1
            last = spawn(*grid_position(count), 0.0, '').name
        spawn_ms = '%.1f' % (1000.0 * (time.monotonic() - spawn_start) / spawned) if spawned else '-'
        files = open_files(pid)  # before measure(): its own subscriber adds a connection
        rate, p99, worst, cpu = measure(pid, '/%s/pose' % last, args.window)
        target = '<= %.0f %%' % TARGET_CPU[size] if size in TARGET_CPU else '-'
        print('| %7d | %14.2f | %12.1f | %12.1f | %17.1f | %10s | %10d | %15s |'
              % (size, rate, p99, worst, cpu, target, files, spawn_ms))
        sys.stdout.flush()
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE) if not args.file_limit else (args.file_limit,) * 2
    print('\nTargets: %.1f Hz, p99 gap <= %.0f ms. Window %.0f s per size, %d cores, load average %.2f.'
          % (TARGET_RATE, TARGET_P99_MS, args.window, os.cpu_count(), os.getloadavg()[0]))
    print('Open-file limit of the node: soft %d, hard %d; %d files open with turtle1 alone.'
          % (soft, hard, files_at_start))
    print('Machine jitter: a bare Python sleep loop on the same tick grid wakes up to %.1f ms late (p99), '
          'which adds to every gap above.' % sleep_loop_p99_lateness(5.0))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--window', type=float, default=10.0, help='seconds measured per size (default 10)')
    parser.add_argument('--sizes', type=int, nargs='+', default=[1, 100, 500, 2000], help='turtle counts')
    parser.add_argument('--file-limit', type=int, default=1024,
                        help='soft and hard open-file limit of the node (default 1024; 0: inherit)')
    parser.add_argument('--before', metavar='DEVEL', help='devel folder of a build to compare this one with')
    parser.add_argument('--turtles', type=int, default=2000, help='turtles of the side-by-side windows')
    parser.add_argument('--rounds', type=int, default=3, help='side-by-side rounds (default 3)')
    parser.add_argument('--sleep-loop', type=float, metavar='SECONDS', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.sleep_loop:
        print(sleep_loop_p99_lateness(args.sleep_loop))
        return

    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port)
    env.pop('DISPLAY', None)
    os.environ['ROS_MASTER_URI'] = env['ROS_MASTER_URI']
    started = []
    try:
        started.append(subprocess.Popen(['roscore', '-p', str(port)], env=env, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL, start_new_session=True))
        wait_until(rosgraph.is_master_online, 30.0, 'roscore on port %d' % port, poll=0.05)
        if args.before:
            side_by_side(args, env, started)
        else:
            sizes_table(args, env, started)
    finally:
        for process in reversed(started):
            stop_process_group(process, 20.0)


if __name__ == '__main__':
    main()
