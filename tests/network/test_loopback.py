"""Security: with the project's environment nothing ROS starts listens beyond loopback (the
library's own rules are tested in src/ros_loopback/test/unit; that it leaves two-machine set-ups
alone, with real ROS nodes, in test_two_hosts.py)."""
import os

from course_testing.network import scenarios
from course_testing.network.rosnet import is_loopback, project_environment


def test_project_environment_preloads_the_library():
    environment = project_environment()
    assert environment.get('ROS_HOSTNAME') == 'localhost'
    preloaded = [path for path in environment.get('LD_PRELOAD', '').split(':')
                 if os.path.basename(path) == 'libros_loopback.so' and os.path.isfile(path)]
    assert preloaded, 'tools/env.sh does not preload libros_loopback.so: LD_PRELOAD=%r' % (
        environment.get('LD_PRELOAD'),)


def test_every_ros_socket_listens_on_loopback_only(processes):
    listening = scenarios.listening_ros_sockets(processes)
    programs = [program for program, _ in listening]
    assert {'roscore', 'rosmaster', 'rosout', 'turtlesim_node', 'circle'} <= set(programs), programs
    # Each of them serves XML-RPC at least: an empty list would mean the test looked in the wrong place.
    assert all(sockets for _, sockets in listening), listening
    assert all(is_loopback(address) for _, sockets in listening for address, _ in sockets), listening
