"""The rules of libros_loopback.so, tried on plain sockets: a wildcard TCP bind goes to loopback
exactly when the address ROS advertises (ROS_HOSTNAME, else ROS_IP) is a loopback one."""
import os
import socket
import subprocess

import pytest

PYTHON = '/usr/bin/python3'


@pytest.fixture(scope='module')
def library():
    """libros_loopback.so as built into the workspace (devel or install space, on LD_LIBRARY_PATH)."""
    for folder in os.environ.get('LD_LIBRARY_PATH', '').split(':'):
        candidate = os.path.join(folder, 'libros_loopback.so')
        if folder and os.path.isfile(candidate):
            return candidate
    raise AssertionError('libros_loopback.so is not on LD_LIBRARY_PATH: '
                         'build ros_loopback and source tools/env.sh')


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
def test_wildcard_tcp_bind_goes_to_loopback_only_when_ros_advertises_loopback(library, environment, expected):
    assert bound_address(library, environment)[0] == expected


def test_ipv6_wildcard_becomes_ipv6_loopback(library):
    assert bound_address(library, {'ROS_HOSTNAME': 'localhost'}, family='ipv6')[0] == '::1'
    assert bound_address(library, {'ROS_IP': '10.200.0.1'}, family='ipv6')[0] == '::'


def test_port_and_explicit_addresses_are_kept(library):
    with socket.socket() as probe:  # a port that is free now
        probe.bind(('127.0.0.1', 0))
        port = probe.getsockname()[1]
    assert bound_address(library, {'ROS_HOSTNAME': 'localhost'}, port=port) == ('127.0.0.1', port)
    assert bound_address(library, {'ROS_HOSTNAME': 'localhost'}, address='127.0.0.1')[0] == '127.0.0.1'


def test_udp_sockets_are_left_alone(library):
    # UDP clients that bind the wildcard before talking to other hosts (DNS tools) must keep working.
    assert bound_address(library, {'ROS_HOSTNAME': 'localhost'}, kind='udp')[0] == '0.0.0.0'
