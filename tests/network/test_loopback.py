"""Security: with the project's environment nothing ROS starts listens beyond loopback, and the
loopback library (ros_loopback) leaves two-machine set-ups alone."""
import os
import subprocess

import pytest

from course_common.testing import wait_until
from rosnet import (PYTHON, descendants, free_port, is_loopback, listening_sockets, node_api,
                    project_environment, start_master)

# Binds a socket to the wildcard address in a fresh process and prints where it ended up.
BIND_PROGRAM = '''
import socket, sys
family = socket.AF_INET6 if sys.argv[1] == "ipv6" else socket.AF_INET
kind = socket.SOCK_DGRAM if sys.argv[2] == "udp" else socket.SOCK_STREAM
sock = socket.socket(family, kind)
sock.bind((sys.argv[3], int(sys.argv[4])))
print(sock.getsockname()[0], sock.getsockname()[1])
'''


def bound_address(library, environment, family='ipv4', kind='tcp', address=None, port=0):
    env = {name: value for name, value in os.environ.items()
           if name not in ('ROS_IP', 'ROS_HOSTNAME', 'LD_PRELOAD')}
    env.update(environment, LD_PRELOAD=library)
    if address is None:
        address = '::' if family == 'ipv6' else '0.0.0.0'
    output = subprocess.run([PYTHON, '-c', BIND_PROGRAM, family, kind, address, str(port)], env=env,
                            stdout=subprocess.PIPE, check=True, universal_newlines=True).stdout.split()
    return output[0], int(output[1])


@pytest.mark.parametrize('environment, expected', [
    ({'ROS_HOSTNAME': 'localhost'}, '127.0.0.1'),
    ({'ROS_HOSTNAME': 'LocalHost'}, '127.0.0.1'),
    ({'ROS_IP': '127.0.0.1'}, '127.0.0.1'),
    ({'ROS_IP': '127.0.1.1'}, '127.0.1.1'),      # peers connect to exactly the advertised address
    ({'ROS_HOSTNAME': '::1'}, '127.0.0.1'),
    ({'ROS_HOSTNAME': 'localhost', 'ROS_IP': '10.200.0.1'}, '127.0.0.1'),  # ROS_HOSTNAME wins, as in ROS
    ({'ROS_HOSTNAME': '', 'ROS_IP': '127.0.0.1'}, '127.0.0.1'),
    ({'ROS_IP': '10.200.0.1'}, '0.0.0.0'),        # two machines: untouched
    ({'ROS_HOSTNAME': 'robot.example.org'}, '0.0.0.0'),
    ({'ROS_HOSTNAME': '10.200.0.2', 'ROS_IP': '127.0.0.1'}, '0.0.0.0'),
    ({'ROS_HOSTNAME': 'localhost.example.org'}, '0.0.0.0'),
    ({'ROS_HOSTNAME': '1270.0.0.1'}, '0.0.0.0'),
    ({}, '0.0.0.0'),                              # no ROS address at all: untouched
], ids=lambda value: repr(value) if isinstance(value, dict) else value)
def test_wildcard_tcp_bind_goes_to_loopback_only_when_ros_advertises_loopback(loopback_library, environment, expected):
    assert bound_address(loopback_library, environment)[0] == expected


def test_ipv6_wildcard_becomes_ipv6_loopback(loopback_library):
    assert bound_address(loopback_library, {'ROS_HOSTNAME': 'localhost'}, family='ipv6')[0] == '::1'
    assert bound_address(loopback_library, {'ROS_IP': '10.200.0.1'}, family='ipv6')[0] == '::'


def test_port_and_explicit_addresses_are_kept(loopback_library):
    port = free_port()
    assert bound_address(loopback_library, {'ROS_HOSTNAME': 'localhost'}, port=port) == ('127.0.0.1', port)
    assert bound_address(loopback_library, {'ROS_HOSTNAME': 'localhost'}, address='127.0.0.1')[0] == '127.0.0.1'


def test_udp_sockets_are_left_alone(loopback_library):
    # UDP clients that bind the wildcard before talking to other hosts (DNS tools) must keep working.
    assert bound_address(loopback_library, {'ROS_HOSTNAME': 'localhost'}, kind='udp')[0] == '0.0.0.0'


def test_project_environment_preloads_the_library(loopback_library):
    environment = project_environment()
    assert environment.get('ROS_HOSTNAME') == 'localhost'
    assert loopback_library in environment.get('LD_PRELOAD', '').split(':'), (
        'tools/env.sh does not preload %s' % loopback_library)


def test_every_ros_socket_listens_on_loopback_only(processes):
    """roscore (rosmaster, roslaunch, the C++ rosout), a C++ course node and the Python turtlesim."""
    port = free_port()
    env = project_environment(ROS_MASTER_URI='http://localhost:%d' % port)
    roscore = start_master(processes, env, port)
    nodes = [processes.start('turtlesim', ['rosrun', 'turtlesim', 'turtlesim_node'], env),
             processes.start('circle', ['rosrun', 'ros_exercises', 'circle'], env)]
    for node in ('/turtlesim', '/circle', '/rosout'):
        wait_until(lambda: node_api(env['ROS_MASTER_URI'], node), 20, 'node %s to register' % node)

    pids = [roscore.pid] + descendants(roscore.pid) + [node.pid for node in nodes]
    sockets = {pid: listening_sockets(pid) for pid in pids}
    programs = {pid: open('/proc/%d/comm' % pid).read().strip() for pid in pids}
    report = {programs[pid]: found for pid, found in sockets.items()}
    # roslaunch, rosmaster, rosout, turtlesim_node, circle: each serves XML-RPC (and topics).
    assert {'roscore', 'rosmaster', 'rosout', 'circle'} <= set(programs.values()), programs
    assert all(sockets[pid] for pid in pids if programs[pid] != 'rosrun'), report
    assert all(is_loopback(address) for found in sockets.values() for address, _ in found), report
