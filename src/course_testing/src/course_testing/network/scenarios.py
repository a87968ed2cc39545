"""The security, load and bad-input scenarios, shared by the tests (which assert on what they
return) and by bench/resilience.py (which prints it as tables).

A scenario works on a Graph: a master, one simulator and probes on the simulator's output topics,
started by `start_turtlesim` or `start_fake_tb3`. Each bad-input case is a function(graph) that
raises AssertionError when the simulator misbehaves and otherwise returns one line saying what
happened, for the table.
"""
import json
import os
import socket
import struct
import subprocess
import time
import xmlrpc.client

import rosgraph
from rosgraph.network import encode_ros_handshake_header

from course_testing.network.rosnet import (HERE, PYTHON, listening_sockets, node_api, now, project_environment,
                                           received_bytes, start_master, start_probe)
from course_common.process_table import descendants
from course_common.processes import free_port
from course_common.waiting import wait_until
from turtlesim.world import TICK_SECONDS

TURTLESIM_POSE_HZ = 1.0 / TICK_SECONDS   # a pose every tick
FAKE_TB3_ODOM_HZ = 30.0
FAKE_TB3_SCAN_HZ = 5.0
RATE_TOLERANCE = 0.05  # relative
FLOOD_RATE = 10000
TWIST_WIRE_BYTES = 4 + 6 * 8  # length prefix, six float64
TURTLESIM = ['rosrun', 'turtlesim', 'turtlesim_node']
POSE_FIELDS = ('x', 'y', 'theta', 'linear_velocity', 'angular_velocity')
ODOM_FIELDS = ('pose.pose.position.x', 'pose.pose.position.y', 'twist.twist.linear.x',
               'twist.twist.angular.z')
# linear.x, linear.y, angular.z: every non-finite value in every field, and finite values so huge
# that a careless integration would overflow to inf or produce inf - inf = NaN.
NON_FINITE_TWISTS = ';'.join([
    'nan,0,0', '0,nan,0', '0,0,nan', 'inf,0,0', '-inf,0,0', '0,inf,0', '0,0,-inf', 'nan,inf,-inf',
    '1.7e308,-1.7e308,1.7e308', '-1.7e308,1.7e308,-1.7e308', '1e-310,0,5e-324'])


class Graph:
    """A master and one simulator, as one test module shares them."""

    def __init__(self, processes, env, master, simulator, node, cmd_vel, probes, speed_field):
        self.processes = processes
        self.env = env
        self.master = master            # the roscore Process
        self.master_uri = env['ROS_MASTER_URI']
        self.simulator = simulator
        self.node = node                # the simulator's node name
        self.cmd_vel = cmd_vel          # the topic that drives it
        self.probes = probes            # {topic: (Probe, expected rate in Hz)}; the first has speed_field
        self.speed_field = speed_field  # the forward speed the simulator reports

    @property
    def main_probe(self):
        return next(iter(self.probes.values()))[0]

    def node_uri(self):
        return wait_until(lambda: node_api(self.master_uri, self.node), 20, 'node %s' % self.node)

    def tool(self, argv, timeout=30):
        """Run a command-line tool against this master; returns the CompletedProcess."""
        return subprocess.run(argv, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              universal_newlines=True, timeout=timeout)

    def assert_alive(self):
        """The simulator runs and still publishes (a fresh message on every probed topic)."""
        assert self.simulator.running(), 'the simulator died:\n' + self.simulator.log()[-3000:]
        for probe, rate in self.probes.values():
            probe.wait_for_messages(1, timeout=max(2.0, 3.0 / rate))

    def assert_obeys(self, speed=0.5):
        """A good command is obeyed (after bad ones: nothing stuck, nothing lost)."""
        publisher = publish(self, 20, 1.0, '%r,0,0' % speed)
        self.main_probe.wait_for(lambda values: abs(values[self.speed_field] - speed) < 1e-6, 10,
                                 'the simulator to report %s m/s' % speed)
        flood_summary(publisher, 20)

    def nan_messages(self):
        return sum(probe.nan_count() for probe, _ in self.probes.values())


def new_master(processes):
    """roscore on a free port with the project's environment; returns (env, roscore Process)."""
    port = free_port()
    env = project_environment(ROS_MASTER_URI='http://localhost:%d' % port)
    return env, start_master(processes, env, port)


def start_turtlesim(processes):
    env, master = new_master(processes)
    simulator = processes.start('turtlesim', TURTLESIM, env)
    pose = start_probe(processes, 'pose', env, '/turtle1/pose', POSE_FIELDS)
    pose.wait_for_messages(1, timeout=30)
    return Graph(processes, env, master, simulator, '/turtlesim', '/turtle1/cmd_vel',
                 {'/turtle1/pose': (pose, TURTLESIM_POSE_HZ)}, 'linear_velocity')


def start_fake_tb3(processes, *launch_args):
    env, master = new_master(processes)
    simulator = processes.start('fake_tb3', ['roslaunch', 'fake_tb3', 'world.launch'] + list(launch_args),
                                env)
    odom = start_probe(processes, 'odom', env, '/odom', ODOM_FIELDS)
    scan = start_probe(processes, 'scan', env, '/scan')
    odom.wait_for_messages(1, timeout=30)
    scan.wait_for_messages(1, timeout=30)
    return Graph(processes, env, master, simulator, '/fake_tb3', '/cmd_vel',
                 {'/odom': (odom, FAKE_TB3_ODOM_HZ), '/scan': (scan, FAKE_TB3_SCAN_HZ)},
                 'twist.twist.linear.x')


def listening_ros_sockets(processes):
    """roscore (roslaunch, rosmaster, the C++ rosout), turtlesim and the pose probe (rospy) and
    ros_exercises circle (roscpp), with the project's environment: [(program, [(address, port)])]
    for each of their processes."""
    graph = start_turtlesim(processes)
    circle = processes.start('circle', ['rosrun', 'ros_exercises', 'circle'], graph.env)
    for node in ('/circle', '/rosout'):
        wait_until(lambda: node_api(graph.master_uri, node), 20, 'node %s to register' % node)
    pids = ([graph.master.pid] + descendants(graph.master.pid)
            + [graph.simulator.pid, graph.main_probe.pid, circle.pid])
    return [(open('/proc/%d/comm' % pid).read().strip(), listening_sockets(pid)) for pid in pids]


def publish(graph, rate, seconds, twists='1,0,1', topic=None):
    """Start flood.py on the graph's cmd_vel (or `topic`); returns the Process."""
    argv = [PYTHON, os.path.join(HERE, 'flood.py'), topic or graph.cmd_vel, str(rate), str(seconds), twists]
    return graph.processes.start('flood', argv, graph.env)


def flood_summary(flood, timeout):
    """What flood.py printed when done: {"sent", "seconds", "subscribers"}."""
    flood.popen.wait(timeout)
    lines = [line for line in flood.log().splitlines() if line.startswith('{')]
    assert lines, 'flood.py printed no summary:\n' + flood.log()[-3000:]
    return json.loads(lines[-1])


def flood(graph, rate=FLOOD_RATE, seconds=3.0, twists='1,0,1'):
    """Flood the simulator's cmd_vel and measure, over the middle of the flood: the rate the
    publisher reached, the rate the simulator read the messages (bytes it read, from its own
    getBusStats, over the size of a Twist on the wire), and the rate and longest gap of every probed
    topic. Returns those numbers in a dict."""
    node_uri = graph.node_uri()
    before_flood = received_bytes(node_uri, graph.cmd_vel)
    publisher = publish(graph, rate, seconds, twists)
    wait_until(lambda: received_bytes(node_uri, graph.cmd_vel) > before_flood, 20,
               'the flood to reach %s' % graph.node)
    start, first = now(), received_bytes(node_uri, graph.cmd_vel)
    time.sleep(seconds - 1.0)  # the measurement window: the flood runs on meanwhile
    end, last = now(), received_bytes(node_uri, graph.cmd_vel)
    summary = flood_summary(publisher, seconds + 20)
    result = {'published_hz': summary['sent'] / summary['seconds'],
              'received_hz': (last - first) / TWIST_WIRE_BYTES / (end - start)}
    result.update(probed_rates(graph, start, end))
    return result


def probed_rates(graph, start, end):
    """{topic: rate, topic + ' max gap': seconds} of every probed topic in [start, end)."""
    rates = {}
    for topic, (probe, _) in graph.probes.items():
        rates[topic] = probe.rate(start, end)
        rates[topic + ' max gap'] = probe.max_gap(start, end)
    return rates


def quiet_rates(graph, seconds=1.5):
    """Rates and longest gaps of every probed topic over the next `seconds`, nothing else going on."""
    start = now()
    slowest, slowest_rate = min(graph.probes.values(), key=lambda probe_and_rate: probe_and_rate[1])
    slowest.wait_for_messages(int(seconds * slowest_rate) + 1, timeout=seconds + 5)
    return probed_rates(graph, start, now())


# --- bad inputs: each returns one line for the table, or raises AssertionError ------------------
def non_finite_commands(graph):
    """NaN, +-inf in every field and overflowing finite values, 1000 a second for a second."""
    warnings_before = graph.simulator.log().count('finite')
    summary = flood_summary(publish(graph, 1000, 1.0, NON_FINITE_TWISTS), 30)
    assert summary['subscribers'] >= 1, summary
    graph.assert_alive()
    log = graph.simulator.log()
    assert log.count('finite') > warnings_before, 'no warning about the non-finite commands:\n' + log[-2000:]
    graph.assert_obeys()
    return '%d sent: warned, ignored, obeys the next good one' % summary['sent']


def wrong_type_on_cmd_vel(graph):
    """std_msgs/String published on the cmd_vel topic: the connection is refused."""
    publisher = graph.processes.start('wrong_type', ['rostopic', 'pub', '-r', '50', graph.cmd_vel,
                                                     'std_msgs/String', 'data: forward'], graph.env)
    wait_until(lambda: 'md5sum' in publisher.log() or not publisher.running(), 20,
               'rostopic pub to report the type mismatch')
    publisher.stop()
    assert 'md5sum' in publisher.log(), publisher.log()[-2000:]
    graph.assert_alive()
    graph.assert_obeys()
    return 'connection refused (md5sum mismatch), obeys the next good command'


def _exchange(host, port, data):
    """Send raw bytes to a server, half-close, return what it answered (b'' if it hung up)."""
    with socket.create_connection((host, int(port)), timeout=10) as connection:
        answer = b''
        try:
            connection.sendall(data)
            connection.shutdown(socket.SHUT_WR)
            for chunk in iter(lambda: connection.recv(65536), b''):
                answer += chunk
        except (ConnectionResetError, BrokenPipeError):
            pass
        return answer


def garbage_on_topic_port(graph):
    """The simulator's TCPROS port: random bytes, an absurd header length followed by 1 MB of
    junk, a header for a topic it does not publish, one with a wrong type and md5sum."""
    topic = next(iter(graph.probes))
    code, text, protocol = xmlrpc.client.ServerProxy(graph.node_uri()).requestTopic(
        '/bad_input', topic, [['TCPROS']])
    assert code == 1, text
    host, port = protocol[1], protocol[2]
    _exchange(host, port, os.urandom(4096))
    _exchange(host, port, struct.pack('<I', 0xFFFFFFF0) + os.urandom(1 << 20))
    unknown_topic = _exchange(host, port, encode_ros_handshake_header(
        {'callerid': '/bad_input', 'topic': '/no/such/topic', 'md5sum': '*', 'type': '*'}))
    wrong_type = _exchange(host, port, encode_ros_handshake_header(
        {'callerid': '/bad_input', 'topic': topic, 'md5sum': '0' * 32, 'type': 'std_msgs/String'}))
    assert b'error=' in unknown_topic and b'error=' in wrong_type, (unknown_topic, wrong_type)
    graph.assert_alive()
    return 'junk dropped; error header for unknown topic and wrong md5sum'


def garbage_service_calls(graph, service):
    """Raw TCPROS to a service: a wrong md5sum, a request of random bytes, a request whose string
    length points 2 GB past its end."""
    uri = rosgraph.Master('/bad_input', master_uri=graph.master_uri).lookupService(service)
    host, port = uri[len('rosrpc://'):].split(':')
    header = {'callerid': '/bad_input', 'service': service, 'md5sum': '*'}

    def request(body):
        return encode_ros_handshake_header(header) + struct.pack('<I', len(body)) + body

    wrong_md5 = _exchange(host, port, encode_ros_handshake_header(dict(header, md5sum='0' * 32)))
    assert b'error=' in wrong_md5, wrong_md5
    replies = [_service_reply(_exchange(host, port, request(body))) for body in (
        os.urandom(64), struct.pack('<fffI', 1, 1, 0, 0x7FFFFFFF) + b'x')]
    assert all(reply is None or not reply[0] for reply in replies), replies
    graph.assert_alive()
    return 'wrong md5sum refused; garbage requests: %s' % ', '.join(
        'hung up' if reply is None else 'failed: ' + reply[1][:60] for reply in replies)


def _service_reply(answer):
    """(ok, payload text) of a raw service answer: the server's header, then an ok byte and a
    length-prefixed payload (the error text when ok is 0); None if the server hung up."""
    header_length = struct.unpack('<I', answer[:4])[0]
    reply = answer[4 + header_length:]
    if not reply:
        return None
    return bool(reply[0]), reply[5:].decode('utf-8', 'replace')


def _http_post(body):
    return b'POST /RPC2 HTTP/1.0\r\nContent-Type: text/xml\r\nContent-Length: %d\r\n\r\n' % len(body) + body


def garbage_xmlrpc(graph, uri=None):
    """A node's XML-RPC port (the simulator's, or `uri`): junk bytes, broken XML, 5 MB of XML, an
    unknown method, known methods with missing or wrongly typed arguments."""
    uri = uri or graph.node_uri()
    host, port = uri.split('//')[1].rstrip('/').split(':')
    answers = [_exchange(host, port, os.urandom(2048) + b'\r\n\r\n'),
               _exchange(host, port, _http_post(b'<?xml version="1.0"?><methodCall><methodName>getPid')),
               _exchange(host, port, _http_post(b'<methodCall><methodName>getPid</methodName><params>'
                                                + b'<param><value>x</value></param>' * 160000))]
    server = xmlrpc.client.ServerProxy(uri)
    wrong_calls = [lambda: server.no_such_method('/bad_input'),
                   lambda: server.getPid(),
                   lambda: server.requestTopic('/bad_input', 7, 'TCPROS'),
                   lambda: server.paramUpdate('/bad_input', 5, [])]
    refused = 0
    for call in wrong_calls:
        try:
            refused += call()[0] != 1
        except xmlrpc.client.Fault:
            refused += 1
    assert refused == len(wrong_calls), 'only %d of %d wrong calls failed' % (refused, len(wrong_calls))
    assert server.getPid('/bad_input')[0] == 1, 'the XML-RPC server no longer answers'
    graph.assert_alive()
    return 'junk, broken and 5 MB requests answered %s; %d wrong calls failed' % (
        '/'.join(answer.split(b' ', 2)[1].decode() if answer.startswith(b'HTTP') else 'closed'
                 for answer in answers), refused)


def call_services(graph, calls):
    """[(service, {field: value})] made by calls.py in one process; its JSON results."""
    result = graph.tool([PYTHON, os.path.join(HERE, 'calls.py'), json.dumps(calls)])
    assert result.returncode == 0, result.stdout
    return json.loads(result.stdout.strip().splitlines()[-1])


# spawn names and what turtlesim must answer: None for a turtle spawned, else part of the error.
SPAWN_NAMES = [('a b', 'Invalid turtle name'), ('1turtle', 'Invalid turtle name'),
               ('tur-tle', 'Invalid turtle name'), ('t\u00fcr', 'Invalid turtle name'),
               ('../up', 'Invalid turtle name'), ('a//b', 'Invalid turtle name'),
               ('line\nbreak', 'Invalid turtle name'), ('%s%n', 'Invalid turtle name'),
               ('nul\x00byte', 'Invalid turtle name'), ('turtle1', 'already exists'),
               ('', None), ('/absolute', None), ('x' * 300, None)]
KILL_NAMES = ['', 'nobody', '*', 'turtle1 ', '%s', '../turtle1']


def odd_turtle_names(graph):
    """spawn and kill with names no turtle may have, unknown ones, and a few valid odd ones."""
    spawned = call_services(graph, [('/spawn', {'name': name, 'x': 3.0, 'y': 3.0, 'theta': 0.0})
                                    for name, _ in SPAWN_NAMES]
                            + [('/spawn', {'name': 'far', 'x': float('nan'), 'y': 1.0, 'theta': 0.0})])
    for (name, error), result in zip(SPAWN_NAMES, spawned):
        if error is None:
            assert result['ok'], (name, result)
        else:
            assert not result['ok'] and error in result['error'], (name, result)
    assert not spawned[-1]['ok'] and 'finite' in spawned[-1]['error'], spawned[-1]
    new_turtles = [result['response']['name'] for result in spawned if result['ok']]
    killed = call_services(graph, [('/kill', {'name': name}) for name in KILL_NAMES + new_turtles])
    assert all(not result['ok'] and 'does not exist' in result['error']
               for result in killed[:len(KILL_NAMES)]), killed
    assert all(result['ok'] for result in killed[len(KILL_NAMES):]), killed
    graph.assert_alive()
    graph.assert_obeys()
    return ('%d names refused with a clear error, %d odd-but-valid spawned and killed, '
            '%d unknown kills refused' % (len(SPAWN_NAMES) - len(new_turtles) + 1, len(new_turtles),
                                          len(KILL_NAMES)))


def wrong_service_fields(graph):
    """What a user types wrong with rosservice: unknown fields, wrong types, too few values."""
    typed = [('/spawn', '{nonsense: 1}'), ('/kill', '{name: [1, 2]}'), ('/spawn', '[1.0]')]
    results = [graph.tool(['rosservice', 'call', service, arguments]) for service, arguments in typed]
    for (service, arguments), result in zip(typed, results):
        assert result.returncode != 0 and 'ERROR' in result.stdout.upper(), (service, arguments,
                                                                             result.stdout)
    graph.assert_alive()
    return 'rosservice refused all %d with an error; node untouched' % len(typed)


COMMON_BAD_INPUTS = [('non-finite cmd_vel', non_finite_commands),
                     ('String on cmd_vel', wrong_type_on_cmd_vel),
                     ('TCPROS junk', garbage_on_topic_port),
                     ('XML-RPC junk', garbage_xmlrpc)]
TURTLESIM_BAD_INPUTS = COMMON_BAD_INPUTS + [
    ('raw /spawn junk', lambda graph: garbage_service_calls(graph, '/spawn')),
    ('rosservice wrong fields', wrong_service_fields),
    ('odd spawn/kill names', odd_turtle_names)]
FAKE_TB3_BAD_INPUTS = COMMON_BAD_INPUTS + [
    ('raw save_picture junk', lambda graph: garbage_service_calls(graph, '/fake_tb3/save_picture'))]
