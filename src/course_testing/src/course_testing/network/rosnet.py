"""What the network tests share: the project's environment, processes that are always cleaned up,
masters on free ports, probes that record a topic from their own process, and the XML-RPC view of a node.

The tests run pytest in one process against several masters, and rospy allows one node per process
bound to one master: so everything that subscribes or publishes runs as a child process (probe.py,
flood.py), which also lets it run inside a network namespace.
"""
import functools
import json
import os
import socket
import subprocess
import threading
import time
import xmlrpc.client

import rosgraph

from course_common.process_table import descendants, new_mark, stop_marked, with_mark
from course_common.processes import stop_process_group
from course_common.waiting import wait_until

HERE = os.path.dirname(os.path.abspath(__file__))
# The workspace: this file is src/course_testing/src/course_testing/network/rosnet.py in it.
ROOT = os.path.abspath(os.path.join(HERE, *[os.pardir] * 5))
PYTHON = '/usr/bin/python3'
ENV_SCRIPT = os.path.join(ROOT, 'tools', 'env.sh')
# Variables a caller's shell may carry that would change what tools/env.sh gives a fresh shell.
CALLER_ROS_VARIABLES = ('ROS_IP', 'ROS_HOSTNAME', 'ROS_MASTER_URI', 'LD_PRELOAD')


@functools.lru_cache(maxsize=None)
def _sourced_environment(given):
    shell = {name: value for name, value in os.environ.items() if name not in CALLER_ROS_VARIABLES}
    shell.update(given)
    output = subprocess.run(['bash', '-c', 'source "$1" >/dev/null && env -0', 'bash', ENV_SCRIPT],
                            env=shell, stdout=subprocess.PIPE, check=True).stdout
    return tuple(tuple(entry.split('=', 1)) for entry in output.decode().split('\0') if '=' in entry)


def project_environment(**given):
    """The environment of a fresh shell that exports `given` (as the README tells users to, e.g.
    ROS_MASTER_URI and ROS_IP for two machines) and then runs `source tools/env.sh`."""
    return dict(_sourced_environment(tuple(sorted(given.items()))))


class Process:
    """A child in its own process group, its output in a log file."""

    def __init__(self, name, argv, env, log_path, stdout=None):
        self.name = name
        self.log_path = log_path
        self._log = open(log_path, 'w')
        # Everything it starts carries the mark, which stop() and kill() find them by.
        self.mark = new_mark('COURSE_TEST_PROCESS')
        self.popen = subprocess.Popen(argv, env=with_mark(self.mark, env), stdin=subprocess.DEVNULL,
                                      stdout=stdout or self._log, stderr=self._log,
                                      start_new_session=True, universal_newlines=True)

    @property
    def pid(self):
        return self.popen.pid

    def running(self):
        return self.popen.poll() is None

    def log(self):
        with open(self.log_path) as log:
            return log.read()

    def stop(self, timeout=10.0):
        """Ctrl-C the group as a terminal would, SIGKILL it if it hangs; returns the exit code.
        Safe to call again, and after kill().

        roslaunch (and so roscore) puts each node in a session of its own, which no process group
        reaches: what carries the process's mark once the group has gone is killed (a node started
        as the group was being stopped too: roscore's rosmaster).
        """
        stop_process_group(self.popen, timeout)
        stop_marked(self.mark)
        self._log.close()
        return self.popen.returncode

    def kill(self):
        """SIGKILL the process and everything it started (a crash, as the rest of the graph sees it)."""
        stop_marked(self.mark)
        self.popen.wait(10)


class Processes:
    """Starts children and stops every one of them at the end of a test, whatever happened."""

    def __init__(self, log_dir):
        self.log_dir = str(log_dir)
        self.started = []

    def start(self, name, argv, env, netns=None, process_class=Process):
        if netns:
            argv = ['ip', 'netns', 'exec', netns] + list(argv)
        log_path = os.path.join(self.log_dir, '%s-%d.log' % (name, len(self.started)))
        process = process_class(name, argv, env, log_path)
        self.started.append(process)
        return process

    def stop_all(self):
        for process in reversed(self.started):
            process.stop()

    def logs(self):
        """Every child's output, for the message of a failed assertion."""
        return '\n'.join('--- %s:\n%s' % (process.name, process.log()[-3000:]) for process in self.started)


class _TimedTransport(xmlrpc.client.Transport):
    """XML-RPC over HTTP whose every wait (connecting, the answer) ends after `seconds`."""

    def __init__(self, seconds):
        super().__init__()
        self.seconds = seconds

    def make_connection(self, host):
        connection = super().make_connection(host)
        connection.timeout = self.seconds
        return connection


def master_pid(uri, seconds=2.0, started=False):
    """The process id the ROS master at `uri` gives, or None when none answers within `seconds` (a
    program that accepts connections on the port and never answers would hold rosgraph's own check,
    which has no time limit, for ever). With `started`, None too until roscore has set /run_id, the
    last of its start: a roscore stopped before then took the stop's whole 10 s to end."""
    master = xmlrpc.client.ServerProxy(uri, transport=_TimedTransport(seconds))
    try:
        code, _text, pid = master.getPid('/network_test')
        if code == 1 and started and not master.hasParam('/network_test', '/run_id')[2]:
            return None
    except (OSError, xmlrpc.client.Error, ValueError):
        return None
    return pid if code == 1 else None


def own_master_answers(uri, roscore):
    """Whether the master at `uri` is the one roscore (its process id) started, and roscore is up:
    not a master another program started on the port first (roscore then ends)."""
    return master_pid(uri, started=True) in descendants(roscore)


# In a network namespace (the test's own cannot reach it): exit 0 once the master of argv[1] is
# roscore's (argv[2]), within argv[3] seconds.
WAIT_IN_NAMESPACE = ('import sys\nfrom course_common.waiting import poll_until\n'
                     'from course_testing.network.rosnet import own_master_answers\n'
                     'uri, roscore, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])\n'
                     'sys.exit(0 if poll_until(lambda: own_master_answers(uri, roscore), seconds, 0.05) else 1)\n')


def start_master(processes, env, port, name='roscore', netns=None, seconds=20):
    """roscore on `port` (env's ROS_MASTER_URI must name it); returns once its master answers and
    roscore has set /run_id (asked from inside `netns` when given). When roscore ends first, or that
    takes more than `seconds`, an AssertionError says so with what roscore printed (its port taken,
    say)."""
    master = processes.start(name, ['roscore', '-p', str(port)], env, netns=netns)
    uri = env['ROS_MASTER_URI']
    asking = None
    if netns:
        asking = subprocess.Popen(['ip', 'netns', 'exec', netns, PYTHON, '-c', WAIT_IN_NAMESPACE, uri,
                                   str(master.pid), str(seconds)], env=env, start_new_session=True)

    def answers():
        if not master.running():
            raise AssertionError('roscore on port %d ended (exit %d) before its master answered; it printed:\n%s'
                                 % (port, master.popen.returncode, master.log()[-2000:]))
        return asking.poll() == 0 if asking else own_master_answers(uri, master.pid)
    try:
        wait_until(answers, seconds, 'the master on port %d' % port, poll=0.05)
    except AssertionError as error:
        if master.running():
            raise AssertionError('%s; roscore printed:\n%s' % (error, master.log()[-2000:])) from None
        raise
    finally:
        if asking:
            stop_process_group(asking)
    return master


def node_api(master_uri, node):
    """The XML-RPC URI of `node` as the master knows it, or None."""
    try:
        return rosgraph.Master('/network_test', master_uri=master_uri).lookupNode(node)
    except (rosgraph.MasterError, OSError):
        return None


def received_bytes(node_uri, topic):
    """Bytes a rospy node has read on `topic`, over all its connections (its getBusStats).

    The message count of getBusStats is no measure of what arrived: rospy counts only the messages
    it keeps for the callback, and with queue_size=1 it drops all but the newest of each read.
    """
    _code, _text, stats = xmlrpc.client.ServerProxy(node_uri).getBusStats('/network_test')
    _published, subscribed, _services = stats
    return sum(connection[1] for name, connections in subscribed if name == topic
               for connection in connections)


class Probe(Process):
    """probe.py: one JSON line per message of a topic (arrival time, NaN found, chosen fields)."""

    def __init__(self, name, argv, env, log_path):
        super().__init__(name, argv, env, log_path, stdout=subprocess.PIPE)
        self.messages = []
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        for line in self.popen.stdout:
            if not line.startswith('{'):  # a log line, not a record
                continue
            record = json.loads(line)
            with self._lock:
                self.messages.append(record)

    def count(self):
        with self._lock:
            return len(self.messages)

    def latest(self):
        with self._lock:
            return self.messages[-1] if self.messages else None

    def between(self, start, end):
        with self._lock:
            return [message for message in self.messages if start <= message['t'] < end]

    def rate(self, start, end):
        """Messages per second in [start, end), from the first to the last arrival in it (a stall
        lowers it; the edges cannot round it)."""
        times = [message['t'] for message in self.between(start, end)]
        return (len(times) - 1) / (times[-1] - times[0]) if len(times) > 1 else 0.0

    def max_gap(self, start, end):
        """The longest time in [start, end) without a message."""
        times = [start] + [message['t'] for message in self.between(start, end)] + [end]
        return max(later - earlier for earlier, later in zip(times, times[1:]))

    def nan_count(self):
        with self._lock:
            return sum(message['nan'] for message in self.messages)

    def wait_for_messages(self, count=1, timeout=20.0):
        start = self.count()
        wait_until(lambda: self.count() >= start + count, timeout,
                   '%d message(s) from %s (log: %s)' % (count, self.name, self.log_path))
        return self.latest()

    def wait_for(self, condition, timeout, what):
        """Wait for a message arriving after this call for which condition(values) is true."""
        start = self.count()

        def arrived():
            with self._lock:
                return next((m for m in self.messages[start:] if condition(m['values'])), None)
        return wait_until(arrived, timeout, what)


def start_probe(processes, name, env, topic, fields=(), netns=None):
    argv = [PYTHON, os.path.join(HERE, 'probe.py'), topic] + list(fields)
    return processes.start(name, argv, env, netns=netns, process_class=Probe)


def now():
    """The clock of the probes' arrival times (CLOCK_MONOTONIC is one clock for every namespace)."""
    return time.monotonic()


def _proc_address(hex_address):
    """'0100007F:1F90' (as /proc/net/tcp writes it: host-order words) -> ('127.0.0.1', 8080)."""
    address, port = hex_address.split(':')
    raw = bytes.fromhex(address)
    # Each 32-bit word is in the host's (little-endian) byte order.
    network_order = b''.join(raw[i:i + 4][::-1] for i in range(0, len(raw), 4))
    family = socket.AF_INET if len(network_order) == 4 else socket.AF_INET6
    return socket.inet_ntop(family, network_order), int(port, 16)


def listening_sockets(pid):
    """[(address, port)] of the TCP sockets `pid` listens on, from /proc (no ss needed)."""
    inodes = set()
    for fd in os.listdir('/proc/%d/fd' % pid):
        try:
            target = os.readlink('/proc/%d/fd/%s' % (pid, fd))
        except OSError:  # closed meanwhile
            continue
        if target.startswith('socket:['):
            inodes.add(target[8:-1])
    sockets = []
    for table in ('tcp', 'tcp6'):
        with open('/proc/%d/net/%s' % (pid, table)) as lines:
            next(lines)
            for line in lines:
                columns = line.split()
                if columns[3] == '0A' and columns[9] in inodes:  # 0A: TCP_LISTEN
                    sockets.append(_proc_address(columns[1]))
    return sockets


def is_loopback(address):
    return address == '::1' or address.startswith('127.')
