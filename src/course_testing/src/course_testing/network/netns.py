"""Two hosts on one machine: two network namespaces joined by a veth pair (iproute2).

Both ends of the pair are created inside the namespaces and the only addresses are 10.200.0.1/24 and
10.200.0.2/24 there: nothing is added to the machine's own network, and nothing can leave it.
Needs root (CAP_NET_ADMIN); the Docker image's non-root user cannot run it.
"""
import os
import re
import subprocess
import time

from course_testing.network import faults
from course_testing.network.rosnet import now, project_environment, start_master, start_probe
from course_testing.network.scenarios import ODOM_FIELDS, POSE_FIELDS, TURTLESIM
from turtlesim.world import TICK_SECONDS

HOST_A_ADDRESS = '10.200.0.1'
HOST_B_ADDRESS = '10.200.0.2'
PREFIX = 'rosres'
IP_TIMEOUT = 10
DRIVEN_TIMEOUT = 40.0  # two masterless hosts starting a master, a simulator and a course node
RESUME_TIMEOUT = 15.0  # TCP retransmits with back-off: the first one after the link is back wins


def _run(*argv):
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            universal_newlines=True, timeout=IP_TIMEOUT)
    if result.returncode != 0:
        raise AssertionError('%s failed: %s' % (' '.join(argv), result.stdout.strip()))
    return result.stdout


def require_root():
    if os.geteuid() != 0:
        raise AssertionError(
            'the two-host tests create network namespaces and need root (CAP_NET_ADMIN); '
            'run them as root, on a CI host rather than in the Docker image')


def remove_stale_namespaces():
    """Namespaces of earlier runs whose pytest died before cleaning up (named after its PID)."""
    for namespace, pid in re.findall(r'^(%s_[ab]_(\d+))' % PREFIX, _run('ip', 'netns', 'list'), re.MULTILINE):
        if not os.path.exists('/proc/%s' % pid):
            subprocess.run(['ip', 'netns', 'delete', namespace], timeout=IP_TIMEOUT)


class TwoHosts:
    """Host A and host B; `cut()` and `restore()` the link between them."""

    def __init__(self):
        tag = os.getpid()
        self.a, self.b = '%s_a_%d' % (PREFIX, tag), '%s_b_%d' % (PREFIX, tag)
        self.link_a, self.link_b = 'vra%d' % tag, 'vrb%d' % tag  # interface names: 15 characters at most

    def create(self):
        require_root()
        remove_stale_namespaces()
        _run('ip', 'netns', 'add', self.a)
        _run('ip', 'netns', 'add', self.b)
        _run('ip', 'link', 'add', self.link_a, 'netns', self.a, 'type', 'veth',
             'peer', 'name', self.link_b, 'netns', self.b)
        for namespace, link, address in ((self.a, self.link_a, HOST_A_ADDRESS),
                                         (self.b, self.link_b, HOST_B_ADDRESS)):
            _run('ip', '-n', namespace, 'addr', 'add', address + '/24', 'dev', link)
            _run('ip', '-n', namespace, 'link', 'set', 'lo', 'up')
            _run('ip', '-n', namespace, 'link', 'set', link, 'up')
        return self

    def delete(self):
        """Remove both namespaces (and with them the veth pair); safe to call twice."""
        for namespace in (self.a, self.b):
            subprocess.run(['ip', 'netns', 'delete', namespace], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, timeout=IP_TIMEOUT)

    def _ends(self):
        return ((self.a, self.link_a), (self.b, self.link_b))

    def cut(self, how):
        """'down': both ends administratively down; 'loss': every packet dropped both ways while the
        link stays up (the blackhole qdisc: what `netem loss 100%` does, without needing the netem
        module, which many kernels lack)."""
        for namespace, link in self._ends():
            if how == 'down':
                _run('ip', '-n', namespace, 'link', 'set', link, 'down')
            else:
                _run('ip', 'netns', 'exec', namespace, 'tc', 'qdisc', 'add', 'dev', link, 'root', 'blackhole')

    def restore(self, how):
        for namespace, link in self._ends():
            if how == 'down':
                _run('ip', '-n', namespace, 'link', 'set', link, 'up')
            else:
                _run('ip', 'netns', 'exec', namespace, 'tc', 'qdisc', 'del', 'dev', link, 'root')

    def environment(self, host):
        """What the README tells a user on each machine to export before `source tools/env.sh`."""
        return project_environment(ROS_MASTER_URI='http://%s:11311' % HOST_A_ADDRESS,
                                   ROS_IP=HOST_A_ADDRESS if host == self.a else HOST_B_ADDRESS)


class RemoteControl:
    """A simulator on host A driven by a course node on host B, watched by a probe on host A."""

    def __init__(self, probe, course_node, driven, stopped, stop_within):
        self.probe = probe              # on host A, beside the simulator: the cut does not touch it
        self.course_node = course_node  # on host B
        self.driven = driven            # values -> True while the course node's commands arrive
        self.stopped = stopped          # values -> True once the simulator stopped the robot
        self.stop_within = stop_within  # the simulator's command timeout, a tick, and a message


def turtlesim_across(processes, hosts):
    """roscore and turtlesim on host A, ros_exercises circle on host B."""
    env_a, env_b = hosts.environment(hosts.a), hosts.environment(hosts.b)
    start_master(processes, env_a, 11311, netns=hosts.a)
    processes.start('turtlesim', TURTLESIM, env_a, netns=hosts.a)
    probe = start_probe(processes, 'pose', env_a, '/turtle1/pose', POSE_FIELDS, netns=hosts.a)
    circle = processes.start('circle', ['rosrun', 'ros_exercises', 'circle'], env_b, netns=hosts.b)
    # turtlesim: 1.0 s without a command, then the next tick publishes the stopped pose.
    return RemoteControl(probe, circle, faults.circling, faults.stopped, 1.0 + 2 * TICK_SECONDS + 0.05)


def fake_tb3_across(processes, hosts):
    """roscore and fake_tb3 (cmd_vel_timeout 1.0 s) on host A, move_turtlebot3's avoid_obstacle.py
    (0.5 m/s ahead while the way is free, a command per scan) on host B."""
    env_a, env_b = hosts.environment(hosts.a), hosts.environment(hosts.b)
    start_master(processes, env_a, 11311, netns=hosts.a)
    processes.start('fake_tb3', ['roslaunch', 'fake_tb3', 'world.launch', 'cmd_vel_timeout:=1.0'],
                    env_a, netns=hosts.a)
    probe = start_probe(processes, 'odom', env_a, '/odom', ODOM_FIELDS, netns=hosts.a)
    driver = processes.start('avoid_obstacle', ['rosrun', 'move_turtlebot3', 'avoid_obstacle.py'],
                             env_b, netns=hosts.b)

    def driven(values):
        return abs(values['twist.twist.linear.x'] - 0.5) < 1e-6

    def stopped(values):
        return values['twist.twist.linear.x'] == 0.0 and values['twist.twist.angular.z'] == 0.0

    # fake_tb3: 1.0 s without a command, a 10 ms physics step, then odom at 30 Hz.
    return RemoteControl(probe, driver, driven, stopped, 1.0 + 0.010 + 1 / 30 + 0.05)


def cut_and_restore(hosts, remote, how):
    """Cut the link `how` while the robot is driven; returns (seconds from the cut until the robot
    stopped, seconds from the link coming back until it was driven again). Checks that it stayed
    still while the link was down."""
    remote.probe.wait_for(remote.driven, DRIVEN_TIMEOUT, 'host B to drive the robot on host A')
    cut = now()
    hosts.cut(how)
    try:
        stopped = remote.probe.wait_for(remote.stopped, remote.stop_within + 5,
                                        'the robot to stop after the cut')
        time.sleep(0.5)  # the link stays down half a second longer: the robot must stay where it stopped
        assert remote.probe.latest()['values'] == stopped['values'], (stopped, remote.probe.latest())
    finally:
        hosts.restore(how)
    restored = now()
    remote.probe.wait_for(remote.driven, RESUME_TIMEOUT, 'control to resume after the link came back')
    return stopped['t'] - cut, now() - restored
