#!/usr/bin/env python3
"""course_web benchmark: what the browser view costs and how late it shows the simulators.

Starts its own master (fake_tb3's empty world launch on a free port), turtlesim, the view on a
free port and headless chromium tabs on it. turtle1 drives a circle (a change at every 16 ms tick),
the TurtleBot3 straight on at 0.2 m/s. Prints Markdown tables:

- latency: from a pose arriving at a ROS subscriber here (turtle1/pose, odom) to the page having
  drawn it (the animation frame after the page drew the pose: the pixels are on screen then);
  poses are matched by their x;
- rates the page draws: turtlesim frames, TurtleBot3 poses and scans per second;
- CPU (% of one core) of turtlesim, fake_tb3, the view node and chromium: with no viewer (turtlesim
  as today, without its ~scene hook; and with it), with one tab, with ten tabs; at 1 and 100 turtles.

Run after `source tools/env.sh`:  /usr/bin/python3 bench/web_bench.py [--window SECONDS]   (~3 min)
Targets: latency median <= 50 ms, p99 <= 150 ms; turtlesim 62.5 Hz; TurtleBot3 poses >= 30 Hz and
every scan (5 Hz); one viewer <= 5 % of a core beyond no viewer.
"""
import argparse
import os
import socket
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
from course_testing.process_table import descendants
from course_testing.processes import free_port, stop_process_group
from course_testing.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import Spawn

# turtlesim exactly as before the ~scene hook: the hook replaced by nothing.
TURTLESIM_WITHOUT_HOOK = '''
import turtlesim.node
class NoScene:
    def __init__(self, world):
        pass
    def after_tick(self):
        pass
turtlesim.node.SceneTopic = NoScene
turtlesim.node.main()
'''


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


class Bench:
    def __init__(self, window):
        self.window = window
        self.processes = []
        self.master_port = free_port()
        os.environ['ROS_MASTER_URI'] = 'http://127.0.0.1:%d' % self.master_port
        self.start(['roslaunch', '-p', str(self.master_port), 'fake_tb3', 'turtlebot3_empty_world.launch'])
        wait_until(lambda: self.node_running('/fake_tb3'), 60, 'fake_tb3', poll=0.2)
        rospy.init_node('web_bench', disable_signals=True)
        self.turtle_commands = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
        self.robot_commands = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
        self.turtlesim = self.view = None
        self.browser = None

    def start(self, argv):
        process = subprocess.Popen(argv, start_new_session=True, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        self.processes.append(process)
        return process

    def stop(self, process):
        stop_process_group(process)
        self.processes.remove(process)

    @staticmethod
    def node_running(name):
        try:
            node_pid(name)
            return True
        except Exception:
            return False

    def start_turtlesim(self, hook):
        if self.turtlesim is not None:
            self.stop(self.turtlesim)
            wait_until(lambda: not self.node_running('/turtlesim'), 30, 'turtlesim to stop', poll=0.2)
        argv = ['rosrun', 'turtlesim', 'turtlesim_node'] if hook else \
            ['/usr/bin/python3', '-c', TURTLESIM_WITHOUT_HOOK]
        self.turtlesim = self.start(argv + ['__name:=turtlesim'])
        wait_until(lambda: self.node_running('/turtlesim'), 30, 'turtlesim', poll=0.2)
        rospy.wait_for_service('/spawn', 30)

    def start_view(self):
        self.view_port = free_port()
        self.view = self.start(['rosrun', 'course_web', 'view', '_port:=%d' % self.view_port])

        def listening():
            with socket.socket() as probe:
                return probe.connect_ex(('127.0.0.1', self.view_port)) == 0
        wait_until(listening, 60, 'the view', poll=0.2)

    def stop_view(self):
        if self.browser is not None:
            self.browser.quit()
            self.browser = None
        if self.view is not None:
            self.stop(self.view)
            self.view = None

    def open_tabs(self, count):
        if self.browser is None:
            self.browser = start_browser()
            self.browser.get('http://localhost:%d/' % self.view_port)
            self.tabs = [self.browser.current_window_handle]
        while len(self.tabs) < count:
            self.browser.switch_to.new_window('tab')
            self.browser.get('http://localhost:%d/' % self.view_port)
            self.tabs.append(self.browser.current_window_handle)
        self.browser.switch_to.window(self.tabs[0])
        wait_until(lambda: self.browser.execute_script('return window.courseWeb.turtlesimFrames') > 10, 60,
                   'the page to draw turtlesim', poll=0.2)

    def drive(self):
        """turtle1 in a circle (commands every 0.1 s from a thread), the robot straight on along +x
        in the empty world (so that each of its poses has an x of its own)."""
        self.robot_commands.publish(self._twist(0.2, 0.0))
        self.driving = True

        def loop():
            while self.driving:
                self.turtle_commands.publish(self._twist(1.0, 0.6))
                time.sleep(0.1)
        threading.Thread(target=loop, daemon=True).start()

    @staticmethod
    def _twist(linear, angular):
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        return twist

    def cpu(self):
        """{what: % of one core} over one window."""
        groups = {'turtlesim': [node_pid('/turtlesim')], 'fake_tb3': [node_pid('/fake_tb3')]}
        if self.view is not None:
            groups['view'] = [node_pid('/course_web')]
        if self.browser is not None:
            browser = self.browser.service.process.pid
            groups['chromium'] = [browser] + descendants(browser)
        before = {what: cpu_of(pids) for what, pids in groups.items()}
        start = time.monotonic()
        time.sleep(self.window)
        elapsed = time.monotonic() - start
        return {what: 100.0 * (cpu_of(pids) - before[what]) / elapsed for what, pids in groups.items()}

    def latency_and_rates(self):
        turtle = Arrivals('/turtle1/pose', Pose, lambda pose: pose.x, 5)
        robot = Arrivals('/odom', Odometry, lambda odom: odom.pose.pose.position.x, 4)
        time.sleep(1.0)
        script = 'return [window.courseWeb.turtlesimFrames, window.courseWeb.tb3Frames, window.courseWeb.scans]'
        counts_before, start = self.browser.execute_script(script), time.monotonic()
        self.browser.execute_script('window.courseWeb.drawn = []')
        time.sleep(self.window)
        counts_after, elapsed = self.browser.execute_script(script), time.monotonic() - start
        time.sleep(0.5)
        drawn = self.browser.execute_script('return window.courseWeb.drawn')
        rates = [(after - before) / elapsed for before, after in zip(counts_before, counts_after)]
        latencies = {'turtlesim': [], 'fake_tb3': []}
        for what, x, drawn_at, on_screen in drawn:
            arrived = (turtle if what == 'turtle1' else robot).latest_before(x, drawn_at)
            if arrived is not None and on_screen is not None:
                latencies['turtlesim' if what == 'turtle1' else 'fake_tb3'].append(on_screen - arrived)
        turtle.subscriber.unregister()
        robot.subscriber.unregister()
        if os.environ.get('WEB_BENCH_DEBUG'):
            print('drawn', [(w, x, d - drawn[0][2]) for w, x, d, _ in drawn if w == 'tb3'][:400], file=sys.stderr)
            print('arrivals', sorted((t[0] - drawn[0][2], x) for x, t in robot.times.items())[:400], file=sys.stderr)
        return latencies, rates

    def spawn(self, count):
        spawn = rospy.ServiceProxy('/spawn', Spawn)
        for index in range(count):
            spawn(1.0 + (index % 10) * 0.9, 1.0 + (index // 10) * 0.9, 0.0, '')

    def close(self):
        self.driving = False
        self.stop_view()
        for process in list(reversed(self.processes)):
            self.stop(process)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--window', type=float, default=10.0, help='seconds per measurement')
    args = parser.parse_args()
    bench = Bench(args.window)
    rows, load = [], [os.getloadavg()[0]]
    try:
        bench.drive()
        for turtles in (1, 100):
            bench.start_turtlesim(hook=False)
            if turtles > 1:
                bench.spawn(turtles - 1)
            rows.append(('%d, no viewer, turtlesim without the hook (as before)' % turtles, bench.cpu()))
            bench.start_turtlesim(hook=True)
            if turtles > 1:
                bench.spawn(turtles - 1)
            rows.append(('%d, no viewer' % turtles, bench.cpu()))
            bench.start_view()
            bench.open_tabs(1)
            if turtles == 1:
                latencies, rates = bench.latency_and_rates()
            rows.append(('%d, one tab' % turtles, bench.cpu()))
            if turtles == 100:
                bench.open_tabs(10)
                rows.append(('%d, ten tabs' % turtles, bench.cpu()))
            load.append(os.getloadavg()[0])
            bench.stop_view()
    finally:
        bench.close()
    print('\n## latency: pose arrives at a subscriber -> drawn and on screen in the page (ms)\n')
    print('| simulator | poses matched | median | p99 | max |')
    print('| --- | --: | --: | --: | --: |')
    for what, values in latencies.items():
        if values:
            print('| %s | %d | %.1f | %.1f | %.1f |' % (what, len(values), percentile(values, 0.5),
                                                    percentile(values, 0.99), max(values)))
        else:
            print('| %s | 0 | - | - | - |' % what)
    print('\n## what the page draws per second (one tab)\n')
    print('| turtlesim frames | TurtleBot3 frames (poses) | scans |')
    print('| --: | --: | --: |')
    print('| %.1f | %.1f | %.1f |' % tuple(rates))
    print('\n## CPU, % of one core (turtle1 driving a circle, the robot straight on)\n')
    print('| turtles, viewers | turtlesim | fake_tb3 | view node | chromium |')
    print('| --- | --: | --: | --: | --: |')
    for label, cpu in rows:
        print('| %s | %s |' % (label, ' | '.join('%.1f' % cpu[what] if what in cpu else '-'
                                                for what in ('turtlesim', 'fake_tb3', 'view', 'chromium'))))
    print('\nload average (1 min) during the runs: %s; %d cores' % (
        ', '.join('%.1f' % value for value in load), os.cpu_count()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
