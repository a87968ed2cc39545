"""rosnet.start_master: a master of the test's own, or a sentence saying why not, with what roscore
printed, and nothing left running either way."""
import os
import socket

import pytest

from course_common.process_table import marked_processes
from course_common.processes import free_port
from course_testing.network.rosnet import Processes, master_pid, start_master
from course_testing.processes import other_master


def environment(port):
    return dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port)


def assert_all_gone(processes):
    for process in processes.started:
        assert not process.running()
        assert marked_processes(process.mark) == [], process.name


def test_the_master_that_answers_is_roscores_own(tmp_path):
    processes = Processes(tmp_path)
    port = free_port()
    try:
        roscore = start_master(processes, environment(port), port)
        answering = master_pid(environment(port)['ROS_MASTER_URI'])
        assert answering is not None and answering != roscore.pid   # rosmaster, roscore's child
        assert answering in marked_processes(roscore.mark)
    finally:
        processes.stop_all()
    assert_all_gone(processes)
    assert master_pid(environment(port)['ROS_MASTER_URI']) is None


def test_a_port_another_master_holds_fails_at_once_with_roscores_words(tmp_path):
    processes = Processes(tmp_path)
    with other_master() as port:
        try:
            # A minute allowed: the error must come from roscore's end, not from the wait.
            with pytest.raises(AssertionError) as raised:
                start_master(processes, environment(port), port, seconds=60)
        finally:
            processes.stop_all()
    assert 'roscore on port %d ended (exit 1) before its master answered' % port in str(raised.value)
    assert 'another roscore/master is already running' in str(raised.value)
    assert_all_gone(processes)


def test_a_port_that_never_answers_ends_the_wait_and_leaves_nothing_running(tmp_path):
    processes = Processes(tmp_path)
    port = free_port()
    with socket.socket() as silent:   # accepts connections, never answers one
        silent.bind(('127.0.0.1', port))
        silent.listen(64)
        try:
            with pytest.raises(AssertionError) as raised:
                start_master(processes, environment(port), port, seconds=3)
        finally:
            # roscore waits on the port too, deaf to Ctrl-C: killed after a second, not ten.
            for process in processes.started:
                process.stop(timeout=1.0)
    assert str(raised.value).startswith('timed out after 3.0 s waiting for the master on port %d; '
                                        'roscore printed:' % port), raised.value
    # What roscore started while it was being stopped (its rosmaster, in a session of its own).
    assert_all_gone(processes)
