"""Two hosts (network namespaces joined by a veth pair): roscore and the simulator on host A, a
course node on host B, set up as the README tells users (ROS_MASTER_URI and ROS_IP, then
`source tools/env.sh`). The robot is driven from host B; the link is cut, the robot stops by the
simulator's command timeout; the link comes back and control resumes without restarting anything.

Needs root: ./test.sh runs this file only as root (not in the Docker image, whose user has no
CAP_NET_ADMIN), and it fails with that sentence when started without.
"""
import pytest

import faults
from course_common.testing import wait_until
from netns import HOST_B_ADDRESS, TwoHosts
from rosnet import is_loopback, listening_sockets, now, start_master, start_probe
from scenarios import POSE_FIELDS

RESUME_TIMEOUT = 15.0  # TCP retransmits with back-off: the first one after the link is back wins
# The simulator stops a turtle 1.0 s after its last command, at the next 16 ms tick; the pose
# that shows it comes on the same host. Measured from the cut, so the last command came before.
STOP_WITHIN = 1.0 + 2 * 0.016 + 0.05


@pytest.fixture
def hosts(processes):
    two_hosts = TwoHosts()
    try:
        yield two_hosts.create()
    finally:
        processes.stop_all()  # before the namespaces go: nothing may be left running inside
        two_hosts.delete()


class PoseGraph:
    """What faults.wait_for_pose needs: a probe on host A, where the simulator runs."""

    def __init__(self, probe):
        self.main_probe = probe


def stop_and_resume(hosts, graph, how, driven):
    """Cut the link `how`; return (seconds until the turtle stopped, seconds until it was driven
    again after the link came back), and check it stayed still while cut."""
    cut = now()
    hosts.cut(how)
    try:
        stopped = graph.main_probe.wait_for(faults.stopped, 5, 'the turtle to stop after the cut')
        still = graph.main_probe.wait_for_messages(30)  # half a second later
        assert (still['values']['x'], still['values']['y']) == (stopped['values']['x'], stopped['values']['y'])
    finally:
        hosts.restore(how)
    restored = now()
    graph.main_probe.wait_for(driven, RESUME_TIMEOUT, 'control to resume after the link came back')
    return stopped['t'] - cut, now() - restored


def test_turtle_driven_from_another_host_stops_when_the_link_is_cut_and_resumes(processes, hosts):
    env_a, env_b = hosts.environment(hosts.a), hosts.environment(hosts.b)
    start_master(processes, env_a, 11311, netns=hosts.a, wait=False)
    processes.start('turtlesim', ['rosrun', 'turtlesim', 'turtlesim_node'], env_a, netns=hosts.a)
    pose = start_probe(processes, 'pose', env_a, '/turtle1/pose', POSE_FIELDS, netns=hosts.a)
    circle = processes.start('circle', ['rosrun', 'ros_exercises', 'circle'], env_b, netns=hosts.b)
    graph = PoseGraph(pose)
    graph.main_probe.wait_for(faults.circling, 40, 'circle on host B to drive the turtle on host A')

    # The C++ node on host B serves on its real address: the loopback library left it alone.
    sockets = listening_sockets(circle.pid)
    assert sockets and not any(is_loopback(address) for address, _ in sockets), sockets

    for how in ('down', 'loss'):
        stop, resume = stop_and_resume(hosts, graph, how, faults.circling)
        assert stop <= STOP_WITHIN, (how, stop)
        assert resume < RESUME_TIMEOUT, (how, resume)
    assert pose.nan_count() == 0
    assert circle.running()
