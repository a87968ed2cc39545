"""The grading session's ROS master: only the rosmaster the session started counts, never a program
that listens on its port first (a master of another grading, or of the student's build), whatever
it answers."""
import os
import threading
import xmlrpc.client
import xmlrpc.server

import pytest
import rosgraph

from course_grader import grading_session
from course_common.waiting import wait_until
from course_testing.processes import other_master


@pytest.fixture
def ros_environment(monkeypatch):
    # Master() and ready() set ROS_MASTER_URI in os.environ (the trusted side's programs read it).
    monkeypatch.setenv('ROS_MASTER_URI', os.environ.get('ROS_MASTER_URI', 'http://localhost:11311'))


def refused(master, port):
    """ready() fails at once with the sentence, and our rosmaster is stopped."""
    try:
        with pytest.raises(RuntimeError) as failure:
            master.ready()
        assert str(failure.value) == ('the ROS master did not start on port %d (another program took the '
                                      'port first)' % port)
    finally:
        master.process.stop(10)


def test_a_master_another_program_started_on_the_port_first_is_not_taken_for_ours(tmp_path, monkeypatch,
                                                                                   ros_environment):
    with other_master() as port:
        monkeypatch.setattr('course_common.processes.free_port', lambda: port)
        master = grading_session.Master(str(tmp_path / 'roscore.txt'))
        assert os.environ['ROS_MASTER_URI'] == master.uri   # at once: the simulators prepared meanwhile have it
        refused(master, port)


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
        refused(master, port)
    finally:
        liar.shutdown()
        liar.server_close()


def test_a_master_shut_down_or_not_alone_on_its_port_and_a_grader_node_shut_down_are_lost(tmp_path, monkeypatch,
                                                                                         ros_environment):
    master = grading_session.Master(str(tmp_path / 'roscore.txt'))
    try:
        wait_until(lambda: master.lost() is None, 30, 'our rosmaster listening')   # as ready() sees it
        ours = grading_session.listening_sockets(master.port)
        with monkeypatch.context() as table:   # the kernel's table as it would read
            table.setattr(grading_session, 'listening_sockets', lambda port: ours | {1})   # another listener too
            assert master.lost() == 'another program than the ROS master listened on its port'
            table.setattr(grading_session, 'listening_sockets', lambda port: set())
            assert master.lost() == 'the ROS master no longer listened on its port'
        assert master.lost() is None
        with monkeypatch.context() as grader:   # a node shut the grader's own node down (its slave API)
            grader.setattr('rospy.core.is_shutdown', lambda: True)
            assert master.lost() == "the grader's own ROS node was shut down"
        # What a node of the submission can do: it reaches the master and may shut it down.
        xmlrpc.client.ServerProxy(master.uri).shutdown('/student', 'taken over')
        wait_until(master.process.ended, 10, 'our rosmaster ended')
        assert master.lost() == 'the ROS master stopped'
    finally:
        master.process.stop(10)
