"""Fault scenarios: a simulator, a course node or the master dies and comes back. Shared by the tests
(which assert on what the functions return) and bench/resilience.py (which prints it).

Each function takes a Graph from scenarios.start_turtlesim and returns a dict of what it measured;
each leaves the graph as it found it (turtlesim running, no course node).
"""
import rosgraph

from course_testing.network.rosnet import now, start_master, start_probe
from course_testing.network.scenarios import POSE_FIELDS, TURTLESIM, TURTLESIM_POSE_HZ, publish

RECOVERY_TIMEOUT = 20.0
# turtlesim zeroes the velocities 1.0 s after the last command; poses say so one tick later.
STOP_TIMEOUT = 1.0 + 0.5


def course_node(graph, name, *argv):
    """Start a course node of the workspace with rosrun, in the graph's environment, once turtle1
    is still: whatever moves it afterwards is this node, not the last commands of an earlier one."""
    # A probe started just before may take seconds to come up on a busy machine: poses first,
    # then stillness within the stop time.
    graph.main_probe.wait_for_messages(1, RECOVERY_TIMEOUT)
    wait_for_pose(graph, stopped, 'turtle1 to be still before %s starts' % name, STOP_TIMEOUT)
    return graph.processes.start(name, ['rosrun'] + list(argv), graph.env)


def driving(graph, driven, name, *argv):
    """course_node(), once its commands move turtle1 (driven(pose values) is true)."""
    node = course_node(graph, name, *argv)
    wait_for_pose(graph, driven, '%s to drive turtle1' % name)
    return node


def circling(values):
    """ros_exercises circle's command: linear.x = angular.z = 1.0."""
    return abs(values['linear_velocity'] - 1.0) < 1e-6 and abs(values['angular_velocity'] - 1.0) < 1e-6


def stopped(values):
    return values['linear_velocity'] == 0.0 and values['angular_velocity'] == 0.0


def wait_for_pose(graph, condition, what, timeout=RECOVERY_TIMEOUT, since=None):
    """Seconds from `since` (default: now) until a pose arriving after this call satisfies `condition`."""
    start = now() if since is None else since
    pose = graph.main_probe.wait_for(condition, timeout, what)
    return pose['t'] - start


def restart_simulator(graph):
    """SIGKILL turtlesim, start it again; returns the new Process."""
    graph.simulator.kill()
    graph.simulator = graph.processes.start('turtlesim', TURTLESIM, graph.env)
    return graph.simulator


def simulator_killed_under_circle(graph):
    """turtlesim dies (SIGKILL) while circle drives it; started again, circle drives the new one."""
    circle = driving(graph, circling, 'circle', 'ros_exercises', 'circle')
    restart_simulator(graph)
    recovered = wait_for_pose(graph, circling, 'circle to drive the restarted turtlesim')
    assert circle.running(), circle.log()[-2000:]
    circle.stop()
    return {'circle drives the restarted turtlesim after': recovered}


def kill_and_restart(graph, driven, name, *rosrun_args):
    """Start a course node, wait until it drives, SIGKILL it: returns (seconds from the kill until
    the turtle stopped, seconds from the restart until it drives again, the restarted Process)."""
    node = driving(graph, driven, name, *rosrun_args)
    killed = now()
    node.kill()
    stop = wait_for_pose(graph, stopped, 'turtle1 to stop without %s' % name, STOP_TIMEOUT, since=killed)
    node = course_node(graph, name, *rosrun_args)
    back = wait_for_pose(graph, driven, 'the restarted %s to drive turtle1' % name)
    return stop, back, node


def course_node_killed(graph):
    """circle dies (SIGKILL): the turtle stops by turtlesim's timeout; circle started again drives."""
    stop, back, circle = kill_and_restart(graph, circling, 'circle', 'ros_exercises', 'circle')
    circle.stop()
    return {'turtle stopped after the kill': stop, 'restarted circle drives after': back}


def teleop_relay_killed(graph):
    """my_turtle_node relays a teleop (10 Hz on cmd_vel_mux/input/teleop): killed, the turtle stops;
    started again it picks the teleop up; turtlesim killed and restarted, the relay drives it again."""
    teleop = publish(graph, 10, 60.0, '0.8,0,-0.4', topic='/cmd_vel_mux/input/teleop')

    def relayed(values):
        return abs(values['linear_velocity'] - 0.8) < 1e-6 and abs(values['angular_velocity'] + 0.4) < 1e-6

    stop, back, relay = kill_and_restart(graph, relayed, 'my_turtle_node', 'my_turtle', 'my_turtle_node')
    restart_simulator(graph)
    simulator_back = wait_for_pose(graph, relayed, 'my_turtle_node to drive the restarted turtlesim')
    relay.stop()
    teleop.stop()
    return {'turtle stopped after the kill': stop,
            'restarted relay drives after': back,
            'relay drives the restarted turtlesim after': simulator_back}


def registered(graph, topic):
    """(publishers, subscribers) of `topic` as the master knows them."""
    publishers, subscribers, _ = rosgraph.Master('/fault_test', master_uri=graph.master_uri).getSystemState()
    return (dict(publishers).get(topic, []), dict(subscribers).get(topic, []))


def master_restarted(graph):
    """The master dies (SIGKILL, with its rosout) while circle drives; a new one starts on the same
    port. Measures what survives and what a user has to do."""
    circle = driving(graph, circling, 'circle', 'ros_exercises', 'circle')
    graph.master.kill()
    wait_for_pose(graph, circling, 'circle to go on driving without a master')
    port = int(graph.master_uri.rsplit(':', 1)[1].strip('/'))
    graph.master = start_master(graph.processes, graph.env, port, name='roscore-again')
    kept_driving = wait_for_pose(graph, circling, 'circle to go on driving with the new master')
    forgotten = registered(graph, '/turtle1/pose')
    # What the user does: start every node again (turtlesim, circle, and the probe, a node too).
    restart_simulator(graph)
    circle.kill()
    graph.main_probe.stop()
    probe = start_probe(graph.processes, 'pose-again', graph.env, '/turtle1/pose', POSE_FIELDS)
    graph.probes['/turtle1/pose'] = (probe, TURTLESIM_POSE_HZ)
    circle = course_node(graph, 'circle', 'ros_exercises', 'circle')
    recovered = wait_for_pose(graph, circling, 'circle to drive turtlesim after both restarted')
    known_again = registered(graph, '/turtle1/pose')
    circle.stop()
    return {'kept_driving_after_s': kept_driving,
            'pose_registrations_on_new_master': forgotten,
            'pose_registrations_after_restarting_nodes': known_again,
            'drives_after_restarting_nodes_s': recovered}
