#!/usr/bin/env python3
"""course_web benchmark: what the browser view costs and how late it shows the simulators.

Starts a master on a free port, then for each set-up (turtlesim alone at 1 and at 100 turtles,
fake_tb3 alone in the empty world, both at 1 and at 100 turtles) the simulators, and measures
them with no view, with the view running and no tab open, with one tab and with ten tabs (headless
chromium). turtle1 drives a circle (a change at every turtlesim tick), the TurtleBot3 straight on at
0.2 m/s. With `--before DEVEL` (the devel folder of another build of this workspace) each set-up
runs with that build's simulators and view too, right before this one's, so both columns come from
the same minutes of the same machine. Prints Markdown tables:

- CPU (% of one core) of turtlesim, fake_tb3, the view node and chromium: the median of `--repeat`
  windows of `--window` seconds each;
- latency, one tab, both simulators: from a pose arriving at a ROS subscriber here (turtle1/pose,
  odom) to the page having drawn it (the animation frame after the page drew the pose: the pixels
  are on screen then); poses are matched by their x;
- rates the page draws: turtlesim frames, distinct TurtleBot3 poses and scans per second.

Run after `source tools/env.sh`:  /usr/bin/python3 bench/web_bench.py [--before DEVEL]   (~8 min a build)
Targets: latency median <= 50 ms, p99 <= 150 ms; turtlesim a frame every tick; TurtleBot3 poses >= 30 Hz and
every scan (5 Hz); one viewer <= 5 % of a core beyond no viewer.
"""
import argparse
import os
import statistics
import subprocess
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from course_testing.browser import start_browser
from course_common.process_table import descendants
from course_common.processes import free_port, port_open, stop_process_group
from course_testing.processes import build_environment
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import Spawn

SETUPS = (('turtlesim', 1), ('turtlesim', 100), ('fake_tb3', 0), ('both', 1), ('both', 100))
VIEWERS = ('no view', 'view, no tab', 'one tab', 'ten tabs')
WHAT = ('turtlesim', 'fake_tb3', 'view', 'chromium')


def cpu_seconds(pid):
    with open('/proc/%d/stat' % pid) as stat:
        fields = stat.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def cpu_of(pids):
    total = 0.0
    for pid in pids:
        try:
            total += cpu_seconds(pid)
        except OSError:
            pass
    return total


def node_pid(name):
    uri = rosgraph.Master('/web_bench').lookupNode(name)
    return xmlrpc.client.ServerProxy(uri).getPid('/web_bench')[2]


def node_running(name):
    try:
        node_pid(name)
        return True
    except Exception:
        return False


def percentile(values, fraction):
    values = sorted(values)
    return values[min(len(values) - 1, int(fraction * (len(values) - 1) + 0.5))]


class Arrivals:
    """x of each pose (rounded as the page gets it) -> wall time it arrived here, in ms."""

    def __init__(self, topic, message_type, x_of, digits):
        self.times, self.lock = {}, threading.Lock()
        self.x_of, self.digits = x_of, digits
        self.subscriber = rospy.Subscriber(topic, message_type, self.arrived, queue_size=100)

    def arrived(self, message):
        now = time.time() * 1000.0
        with self.lock:
            self.times.setdefault(round(self.x_of(message), self.digits), []).append(now)

    def latest_before(self, x, moment):
        """When the last pose with this x arrived before `moment` (ms), or None."""
        with self.lock:
            times = [t for t in self.times.get(round(x, self.digits), ()) if t <= moment]
        return times[-1] if times else None


class Run:
    """One build's simulators, view and browser on the bench's master."""

    def __init__(self, bench, environment):
        self.bench, self.environment = bench, environment
        self.processes = []
        self.view = self.browser = None
        self.tabs = []

    def start(self, argv):
        process = subprocess.Popen(argv, start_new_session=True, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL, env=self.environment)
        self.processes.append(process)
        return process

    def start_simulators(self, simulators, turtles):
        # fake_tb3's launch puts the master on simulated time (/use_sim_time): a node started after
        # it runs on that time. Each run starts from wall time, fake_tb3 first, as labs do.
        if rospy.has_param('/use_sim_time'):
            rospy.delete_param('/use_sim_time')
        if simulators in ('fake_tb3', 'both'):
            self.start(['roslaunch', '-p', str(self.bench.master_port), 'fake_tb3',
                        'turtlebot3_empty_world.launch'])
            wait_until(lambda: node_running('/fake_tb3'), 60, 'fake_tb3', poll=0.2)
        if simulators in ('turtlesim', 'both'):
            self.start(['rosrun', 'turtlesim', 'turtlesim_node', '__name:=turtlesim'])
            wait_until(lambda: node_running('/turtlesim'), 30, 'turtlesim', poll=0.2)
            rospy.wait_for_service('/spawn', 30)
            spawn = rospy.ServiceProxy('/spawn', Spawn)
            for index in range(turtles - 1):
                spawn(1.0 + (index % 10) * 0.9, 1.0 + (index // 10) * 0.9, 0.0, '')

    def start_view(self):
        self.view_port = free_port()
        self.view = self.start(['rosrun', 'course_web', 'view', '__name:=course_web', '_port:=%d' % self.view_port])
        wait_until(lambda: port_open(self.view_port), 60, 'the view', poll=0.2)
        time.sleep(3.0)  # settle: its start-up is not what is measured

    def open_tabs(self, count, simulators):
        if self.browser is None:
            self.browser = start_browser()
            self.browser.get('http://localhost:%d/' % self.view_port)
            self.tabs = [self.browser.current_window_handle]
        while len(self.tabs) < count:
            self.browser.switch_to.new_window('tab')
            self.browser.get('http://localhost:%d/' % self.view_port)
            self.tabs.append(self.browser.current_window_handle)
        counter = 'tb3Frames' if simulators == 'fake_tb3' else 'turtlesimFrames'
        for tab in reversed(self.tabs):
            self.browser.switch_to.window(tab)
            wait_until(lambda: self.browser.execute_script('return window.courseWeb.%s' % counter) > 10, 60,
                       'the page to draw', poll=0.2)
        time.sleep(1.0)

    def cpu(self):
        """{what: % of one core}: the median of the bench's windows."""
        groups = {'turtlesim': '/turtlesim', 'fake_tb3': '/fake_tb3', 'view': '/course_web'}
        groups = {what: [node_pid(name)] for what, name in groups.items() if node_running(name)}
        if self.browser is not None:
            browser = self.browser.service.process.pid
            groups['chromium'] = [browser] + descendants(browser)
        samples = {what: [] for what in groups}
        for _ in range(self.bench.repeat):
            before, start = {what: cpu_of(pids) for what, pids in groups.items()}, time.monotonic()
            time.sleep(self.bench.window)
            elapsed = time.monotonic() - start
            for what, pids in groups.items():
                samples[what].append(100.0 * (cpu_of(pids) - before[what]) / elapsed)
        return {what: statistics.median(values) for what, values in samples.items()}

    def latency_and_rates(self):
        """Latencies per simulator (ms) and what the page drew per second, in the first tab."""
        browser = self.browser
        browser.switch_to.window(self.tabs[0])
        turtle = Arrivals('/turtle1/pose', Pose, lambda pose: pose.x, 5)
        robot = Arrivals('/odom', Odometry, lambda odom: odom.pose.pose.position.x, 4)
        time.sleep(1.0)
        browser.execute_script('window.courseWeb.drawn = []')
        scans, start = browser.execute_script('return window.courseWeb.scans'), time.monotonic()
        time.sleep(self.bench.window * self.bench.repeat)
        drawn = browser.execute_script('return window.courseWeb.drawn')
        scans, elapsed = browser.execute_script('return window.courseWeb.scans') - scans, time.monotonic() - start
        time.sleep(0.5)
        turtle.subscriber.unregister()
        robot.subscriber.unregister()
        latencies = {'turtlesim': [], 'fake_tb3': []}
        for what, x, drawn_at, on_screen in drawn:
            arrived = (turtle if what == 'turtle1' else robot).latest_before(x, drawn_at)
            if arrived is not None and on_screen is not None:
                latencies['turtlesim' if what == 'turtle1' else 'fake_tb3'].append(on_screen - arrived)
        # One 'turtle1' entry per turtlesim frame drawn, one 'tb3' entry per distinct pose drawn.
        rates = (sum(entry[0] == 'turtle1' for entry in drawn) / elapsed,
                 sum(entry[0] == 'tb3' for entry in drawn) / elapsed, scans / elapsed)
        return latencies, rates

    def stop_all(self):
        if self.browser is not None:
            self.browser.quit()
            self.browser, self.tabs = None, []
        for process in reversed(self.processes):
            stop_process_group(process)
        self.processes, self.view = [], None
        wait_until(lambda: not node_running('/turtlesim') and not node_running('/fake_tb3')
                   and not node_running('/course_web'), 30, 'the nodes to stop', poll=0.2)

    def measure(self, simulators, turtles):
        """{viewers: cpu}, and (latencies, rates) for both simulators."""
        rows, quality = {}, None
        try:
            self.start_simulators(simulators, turtles)
            rows['no view'] = self.cpu()
            self.start_view()
            rows['view, no tab'] = self.cpu()
            self.open_tabs(1, simulators)
            rows['one tab'] = self.cpu()
            if simulators == 'both':
                quality = self.latency_and_rates()
            self.open_tabs(10, simulators)
            rows['ten tabs'] = self.cpu()
        finally:
            self.stop_all()
        return rows, quality


class Bench:
    def __init__(self, window, repeat):
        self.window, self.repeat = window, repeat
        self.master_port = free_port()
        os.environ['ROS_MASTER_URI'] = 'http://127.0.0.1:%d' % self.master_port
        self.master = subprocess.Popen(['roscore', '-p', str(self.master_port)], start_new_session=True,
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        wait_until(lambda: node_running('/rosout'), 60, 'the master', poll=0.2)
        rospy.init_node('web_bench', disable_signals=True)
        self.turtle_commands = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
        self.robot_commands = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
        self.driving = True
        self.robot_commands.publish(self._twist(0.2, 0.0))
        threading.Thread(target=self._drive_turtle, daemon=True).start()

    def _drive_turtle(self):
        while self.driving:
            self.turtle_commands.publish(self._twist(1.0, 0.6))
            time.sleep(0.1)

    @staticmethod
    def _twist(linear, angular):
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        return twist

    def close(self):
        self.driving = False
        stop_process_group(self.master)


def print_tables(bench, builds, cpu, quality, load):
    print('\n## CPU, %% of one core (median of %d windows of %.0f s; turtle1 driving a circle, the robot '
          'straight on)\n' % (bench.repeat, bench.window))
    names = list(builds)
    print('| simulators, turtles | viewers | %s |' % ' | '.join(
        '%s %s' % (what, name) if len(names) > 1 else what for what in WHAT for name in names))
    print('| --- | --- | %s |' % ' | '.join('--:' for _ in WHAT for _ in names))
    for setup in SETUPS:
        label = setup[0] if setup[0] == 'fake_tb3' else '%s, %d' % setup
        for viewers in VIEWERS:
            cells = []
            for what in WHAT:
                for name in names:
                    value = cpu.get((name, setup), {}).get(viewers, {}).get(what)
                    cells.append('-' if value is None else '%.1f' % value)
            print('| %s | %s | %s |' % (label, viewers, ' | '.join(cells)))
    print('\n## latency, one tab, both simulators: pose arrives at a subscriber -> drawn and on screen (ms)\n')
    print('| build | turtles | simulator | poses matched | median | p99 | max |')
    print('| --- | --: | --- | --: | --: | --: | --: |')
    for (name, turtles), (latencies, _) in sorted(quality.items()):
        for what, values in latencies.items():
            if values:
                print('| %s | %d | %s | %d | %.1f | %.1f | %.1f |' % (
                    name, turtles, what, len(values), percentile(values, 0.5), percentile(values, 0.99), max(values)))
            else:
                print('| %s | %d | %s | 0 | - | - | - |' % (name, turtles, what))
    print('\n## what the page draws per second (one tab, both simulators)\n')
    print('| build | turtles | turtlesim frames | distinct TurtleBot3 poses | scans |')
    print('| --- | --: | --: | --: | --: |')
    for (name, turtles), (_, rates) in sorted(quality.items()):
        print('| %s | %d | %.1f | %.1f | %.1f |' % ((name, turtles) + tuple(rates)))
    print('\nload average (1 min) during the runs: %s; %d cores' % (
        ', '.join('%.1f' % value for value in load), os.cpu_count()))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--window', type=float, default=4.0, help='seconds per CPU window')
    parser.add_argument('--repeat', type=int, default=3, help='windows per measurement (the median is kept)')
    parser.add_argument('--before', metavar='DEVEL', help='devel folder of a build to measure beside this one')
    parser.add_argument('--setups', nargs='*', type=int, help='only these set-ups (indices into %s)' % (SETUPS,))
    args = parser.parse_args()
    bench = Bench(args.window, args.repeat)
    builds = {}
    if args.before:
        builds['before'] = build_environment(args.before)
    builds['after' if args.before else 'this build'] = dict(os.environ)
    cpu, quality, load = {}, {}, [os.getloadavg()[0]]
    try:
        for index, setup in enumerate(SETUPS):
            if args.setups and index not in args.setups:
                continue
            for name, environment in builds.items():
                rows, measured = Run(bench, environment).measure(*setup)
                cpu[(name, setup)] = rows
                if measured is not None:
                    quality[(name, setup[1])] = measured
                load.append(os.getloadavg()[0])
                print('done: %s, %s' % (name, setup), file=sys.stderr, flush=True)
    finally:
        bench.close()
    print_tables(bench, builds, cpu, quality, load)
    return 0


if __name__ == '__main__':
    sys.exit(main())
