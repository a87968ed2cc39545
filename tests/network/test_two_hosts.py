"""Two hosts (network namespaces joined by a veth pair): roscore and the simulator on host A, a
course node on host B, set up as the README tells users (ROS_MASTER_URI and ROS_IP, then
`source tools/env.sh`). The robot is driven from host B; the link is cut (interfaces down, then
every packet dropped): the robot stops by the simulator's command timeout; the link comes back and
control resumes without restarting anything.

Needs root: ./test.sh runs this file only as root (not in the Docker image, whose user has no
CAP_NET_ADMIN); started without, it fails with a sentence saying so.
"""
import pytest

from course_testing.network.netns import RESUME_TIMEOUT, TwoHosts, cut_and_restore, fake_tb3_across, turtlesim_across
from course_testing.network.rosnet import is_loopback, listening_sockets


@pytest.fixture
def hosts(processes):
    two_hosts = TwoHosts()
    try:
        yield two_hosts.create()
    finally:
        processes.stop_all()  # before the namespaces go: nothing may be left running inside
        two_hosts.delete()


@pytest.mark.parametrize('across', [turtlesim_across, fake_tb3_across], ids=['turtlesim', 'fake_tb3'])
def test_robot_driven_from_another_host_stops_when_the_link_is_cut_and_resumes(processes, hosts, across):
    remote = across(processes, hosts)
    for how in ('down', 'loss'):
        stop, resume = cut_and_restore(hosts, remote, how)
        assert stop <= remote.stop_within, (how, stop)
        assert resume < RESUME_TIMEOUT, (how, resume)
    assert remote.probe.nan_count() == 0
    assert remote.course_node.running()
    # The node on host B serves on its real address: with ROS_IP set the loopback library is idle.
    sockets = listening_sockets(remote.course_node.pid)
    assert sockets and not any(is_loopback(address) for address, _ in sockets), sockets
