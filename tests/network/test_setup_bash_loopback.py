"""Security as a student opens a terminal: a fresh shell that only runs `source devel/setup.bash`
(as the slides teach, no tools/env.sh) gets the loopback default from the workspace's environment
hooks: the master, a C++ node and a Python node listen on loopback only. With a real ROS_IP the
hooks stay out of the way (two machines)."""
import os
import socket
import subprocess

import pytest

from course_testing.network.rosnet import ROOT, is_loopback, listening_sockets, node_api, start_master
from course_common.process_table import descendants
from course_common.processes import free_port
from course_common.waiting import wait_until

DEVEL = os.path.join(os.environ.get('CATKIN_BUILD_BASE', ROOT), 'devel')
LIBRARY = os.path.join(DEVEL, 'lib', 'libros_loopback.so')


def terminal_environment(**exported):
    """The environment of a new terminal (nothing inherited but HOME and a plain PATH) that exports
    `exported` and then sources devel/setup.bash."""
    shell = {'HOME': os.environ.get('HOME', '/tmp'), 'PATH': '/usr/local/bin:/usr/bin:/bin'}
    if 'ROS_HOME' in os.environ:   # ./test.sh's: the masters' logs stay with the run's
        shell['ROS_HOME'] = os.environ['ROS_HOME']
    shell.update(exported)
    output = subprocess.run(['env', '-i'] + ['%s=%s' % item for item in shell.items()]
                            + ['bash', '-c', 'source "$1" >/dev/null && env -0', 'bash',
                               os.path.join(DEVEL, 'setup.bash')],
                            stdout=subprocess.PIPE, check=True, timeout=60).stdout
    return dict(entry.split('=', 1) for entry in output.decode().split('\0') if '=' in entry)


def machine_address():
    """An address of this machine that other machines could reach (None without a route)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.connect(('192.0.2.1', 9))  # no packet is sent: only the route is looked up
        except OSError:
            return None
        return probe.getsockname()[0]


def start_graph(processes, env):
    """roscore, ros_exercises' circle (roscpp) and `rostopic pub` (rospy) on a free port; returns
    {program: [(address, port)]} of every process they run, once each serves XML-RPC."""
    port = free_port()
    env = dict(env, ROS_MASTER_URI='http://localhost:%d' % port)
    master = start_master(processes, env, port)
    cpp = processes.start('circle', ['rosrun', 'ros_exercises', 'circle'], env)
    python = processes.start('rostopic', ['rostopic', 'pub', '-r', '5', '/setup_bash_probe',
                                          'std_msgs/String', 'hello'], env)
    wait_until(lambda: node_api(env['ROS_MASTER_URI'], '/circle'), 30, 'the C++ node to register')
    pids = [master.pid] + descendants(master.pid) + [cpp.pid, python.pid]
    programs = lambda: {  # noqa: E731
        open('/proc/%d/comm' % pid).read().strip(): listening_sockets(pid) for pid in pids}
    # rostopic pub serves its topic once it has advertised it: two listening sockets (XML-RPC, TCPROS).
    wait_until(lambda: len(programs().get('rostopic', [])) >= 2 and programs().get('rosout'), 30,
               'the Python node and rosout to listen')
    return programs()


def test_the_hooks_set_the_loopback_default():
    env = terminal_environment()
    assert env.get('ROS_HOSTNAME') == 'localhost'
    assert env.get('LD_PRELOAD') == LIBRARY
    assert env['PATH'].split(':')[0] == '/usr/bin'
    # Sourcing again (a second `source`, another workspace's setup) adds nothing.
    twice = subprocess.run(['bash', '-c', 'source "$1"; source "$1"; echo "$PATH|$LD_PRELOAD"', 'bash',
                            os.path.join(DEVEL, 'setup.bash')], env=env, stdout=subprocess.PIPE,
                           universal_newlines=True, check=True).stdout.strip()
    assert twice == '%s|%s' % (env['PATH'], LIBRARY)


def test_nothing_listens_beyond_loopback_after_source_devel_setup(processes):
    listening = start_graph(processes, terminal_environment())
    assert {'rosmaster', 'rosout', 'circle', 'rostopic'} <= set(listening), listening
    wildcard = {program: sockets for program, sockets in listening.items()
                if any(not is_loopback(address) for address, _ in sockets)}
    assert not wildcard, 'listening beyond loopback: %r' % wildcard


@pytest.mark.parametrize('variable', ['ROS_IP', 'ROS_HOSTNAME'])
def test_a_real_address_turns_the_default_off(processes, variable):
    address = machine_address()
    if address is None:
        pytest.skip('this machine has no route to other machines: no real address to give ROS')
    # As after `export ROS_HOSTNAME=localhost` left by an earlier sourcing, then the user's ROS_IP.
    stale = {'ROS_HOSTNAME': 'localhost'} if variable == 'ROS_IP' else {}
    env = terminal_environment(**dict(stale, **{variable: address}))
    assert env.get('ROS_HOSTNAME') == (address if variable == 'ROS_HOSTNAME' else None)
    assert 'libros_loopback' not in env.get('LD_PRELOAD', '')
    listening = start_graph(processes, env)
    # roscpp's XML-RPC server binds every interface again, as two machines need.
    assert any(address == '0.0.0.0' or address == '::' for address, _ in listening['circle']), listening
