"""The grading session's ROS master: only the rosmaster the session started counts, never a program
that listens on its port first (a master of another grading, or of the student's build), whatever
it answers."""
import os
import subprocess
import threading
import xmlrpc.server

import pytest
import rosgraph

from course_common.processes import free_port, stop_process_group
from course_common.waiting import wait_until
from course_grader import grading_session


@pytest.fixture
def ros_environment(monkeypatch):
    # Master() and ready() set ROS_MASTER_URI in os.environ (the trusted side's programs read it).
    monkeypatch.setenv('ROS_MASTER_URI', os.environ.get('ROS_MASTER_URI', 'http://localhost:11311'))


def test_a_master_another_program_started_on_the_port_first_is_not_taken_for_ours(tmp_path, monkeypatch,
                                                                                   ros_environment):
    port = free_port()
    other = subprocess.Popen(['rosmaster', '--core', '-p', str(port)], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        wait_until(lambda: rosgraph.Master('/test', master_uri='http://localhost:%d' % port).is_online(), 30,
                   'the other master')
        monkeypatch.setattr('course_common.processes.free_port', lambda: port)
        master = grading_session.Master(str(tmp_path / 'roscore.txt'))
        assert os.environ['ROS_MASTER_URI'] == master.uri   # at once: the simulators prepared meanwhile have it
        try:
            with pytest.raises(RuntimeError) as failure:
                master.ready()
            assert str(failure.value) == ('the ROS master did not start on port %d (another program took the '
                                          'port first)' % port)
        finally:
            master.process.stop(10)
    finally:
        stop_process_group(other)



def test_a_program_on_the_port_that_answers_with_our_masters_process_id_is_not_taken_for_ours(
        tmp_path, monkeypatch, ros_environment):
    # What a student's build could start: it reads the port and the process id of the session's
    # rosmaster in /proc, and listens there first; what it answers is its own to say.
    claimed = {}
    liar = xmlrpc.server.SimpleXMLRPCServer(('127.0.0.1', 0), logRequests=False)
    liar.register_function(lambda caller_id: [1, '', claimed.get('pid', 0)], 'getPid')
    threading.Thread(target=liar.serve_forever, daemon=True).start()
    try:
        port = liar.server_address[1]
        monkeypatch.setattr('course_common.processes.free_port', lambda: port)
        master = grading_session.Master(str(tmp_path / 'roscore.txt'))
        claimed['pid'] = master.process.process.pid
        assert rosgraph.Master('/test', master_uri=master.uri).getPid() == master.process.process.pid
        try:
            with pytest.raises(RuntimeError) as failure:
                master.ready()
            assert str(failure.value) == ('the ROS master did not start on port %d (another program took the '
                                          'port first)' % port)
        finally:
            master.process.stop(10)
    finally:
        liar.shutdown()
        liar.server_close()
