"""The processes found in /proc by parent, user and mark, and stopped wherever they went; whose socket
listens on a port."""
import os
import signal
import socket
import subprocess

import pytest

from course_common.process_table import (command_line, descendants, listening_sockets, marked_processes, new_mark,
                                          socket_inodes, stop_marked, user_processes, with_mark)
from course_common.waiting import wait_until


def test_what_escaped_to_init_in_sessions_of_its_own_is_found_and_stopped_by_its_mark():
    # As roslaunch's nodes: in a session of their own, reparented to init when their parent goes.
    mark = new_mark('COURSE_TEST_MARK')
    env = with_mark(mark)
    subprocess.run(['setsid', '-f', 'sleep', '600'], env=env, check=True)
    subprocess.run(['setsid', '-f', 'bash', '-c', 'sleep 600 & sleep 600'], env=env, check=True)
    try:
        # Waited for by command line: a child bash has forked but not yet become its sleep for a moment.
        wait_until(lambda: sorted(command_line(pid).split(' ', 1)[1] for pid in marked_processes(mark)) ==
                   ['bash -c sleep 600 & sleep 600'] + ['sleep 600'] * 3, 10, 'the three sleeps and their bash')
        assert marked_processes(new_mark('COURSE_TEST_MARK')) == []   # another mark, none of them
    finally:
        assert stop_marked(mark) == 4
    assert marked_processes(mark) == []


def test_the_processes_below_one_are_its_children_and_theirs():
    parent = subprocess.Popen(['bash', '-c', 'sleep 600 & sleep 600 & wait'])
    try:
        # By command line: a forked bash is a bash until it execs its sleep.
        wait_until(lambda: [command_line(pid).split(' ', 1)[1] for pid in descendants(parent.pid)] ==
                   ['sleep 600'] * 2, 10, 'the two sleeps')
        assert parent.pid in descendants(os.getpid())
        assert set(descendants(parent.pid)) < set(descendants(os.getpid()))
    finally:
        for pid in descendants(parent.pid):
            os.kill(pid, signal.SIGKILL)
        parent.wait()
    assert descendants(parent.pid) == []


def test_the_processes_of_a_user_are_found_but_not_the_dead_ones():
    sleeper = subprocess.Popen(['sleep', '600'])
    try:
        assert sleeper.pid in user_processes(os.getuid())
        assert sleeper.pid not in user_processes(os.getuid() + 1)
    finally:
        sleeper.kill()
    # Killed, not yet waited for: a zombie (PID 1 of a container may never reap it) is not looked for.
    wait_until(lambda: sleeper.pid not in user_processes(os.getuid()), 10, 'the killed sleep to be a zombie')
    assert command_line(sleeper.pid) == '%d ' % sleeper.pid   # a zombie has no command line left
    sleeper.wait()
    assert command_line(sleeper.pid) == '%d (gone)' % sleeper.pid


def test_the_socket_listening_on_a_port_is_found_among_its_processs_own():
    with socket.socket() as server:
        server.bind(('127.0.0.1', 0))
        server.listen()
        port = server.getsockname()[1]
        listening = listening_sockets(port)
        assert len(listening) == 1 and listening <= socket_inodes(os.getpid())
        sleeper = subprocess.Popen(['sleep', '60'])
        try:
            assert not listening & socket_inodes(sleeper.pid)
        finally:
            sleeper.kill()
            sleeper.wait()
        assert socket_inodes(sleeper.pid) == set()   # gone
    assert listening_sockets(port) == set()


def test_a_socket_listening_on_ipv6_loopback_is_found_too():
    if not socket.has_ipv6 or not os.path.exists('/proc/net/tcp6'):
        pytest.skip('no IPv6 on this machine')
    with socket.socket(socket.AF_INET6) as server:
        try:
            server.bind(('::1', 0))
        except OSError:
            pytest.skip('IPv6 without a loopback address on this machine')
        server.listen()
        assert listening_sockets(server.getsockname()[1]) <= socket_inodes(os.getpid())
        assert len(listening_sockets(server.getsockname()[1])) == 1
