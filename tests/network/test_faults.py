"""Faults: the simulator, a course node or the master dies and is started again.

What recovers by itself: nodes reconnect to a restarted simulator or course node, because the master
tells them where the new one is. What does not: a restarted master knows nothing of the nodes that
registered with the old one (ROS 1 nodes never register again); connections made before keep working,
but nothing new connects until the user starts the nodes again.
"""
import pytest

from course_testing.network import faults, scenarios


@pytest.fixture(scope='module')
def graph(module_processes):
    return scenarios.start_turtlesim(module_processes)


def test_simulator_killed_and_restarted_under_a_running_course_node(graph):
    result = faults.simulator_killed_under_circle(graph)
    assert result['circle drives the restarted turtlesim after'] < faults.RECOVERY_TIMEOUT


def test_course_node_killed_stops_the_turtle_and_picks_up_when_restarted(graph):
    result = faults.course_node_killed(graph)
    # turtlesim's 1 s timeout after the last command, a tick, and the pose on its way.
    assert result['turtle stopped after the kill'] < faults.STOP_TIMEOUT


def test_teleop_relay_killed_and_simulator_restarted(graph):
    result = faults.teleop_relay_killed(graph)
    assert result['turtle stopped after the kill'] < faults.STOP_TIMEOUT
    assert result['relay drives the restarted turtlesim after'] < faults.RECOVERY_TIMEOUT


def test_no_nan_published_through_the_faults(graph):
    assert graph.nan_messages() == 0


def test_master_restarted_keeps_connections_but_needs_the_nodes_started_again(processes):
    graph = scenarios.start_turtlesim(processes)
    result = faults.master_restarted(graph)
    # Connections made before the master died carry on, with no master and with the new one.
    assert result['kept_driving_after_s'] < 1.0
    # The new master has never heard of turtlesim's pose topic or of circle ...
    assert result['pose_registrations_on_new_master'] == ([], [])
    # ... until the nodes are started again, and then everything works.
    publishers, subscribers = result['pose_registrations_after_restarting_nodes']
    assert publishers == ['/turtlesim'] and '/circle' in subscribers
