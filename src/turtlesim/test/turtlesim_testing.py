"""What the turtlesim rostests share: watching topics, rosout lines and the master's view of the graph."""
import math
import xmlrpc.client

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.world import COMMAND_TIMEOUT, TICK_SECONDS

# The ticks one velocity command moves a turtle: its timeout's worth, the last tick before it expires.
ONE_COMMAND_TICKS = math.ceil(COMMAND_TIMEOUT / TICK_SECONDS)
LEVEL_NAMES = {Log.DEBUG: 'DEBUG', Log.INFO: 'INFO', Log.WARN: 'WARN', Log.ERROR: 'ERROR', Log.FATAL: 'FATAL'}


class RosoutWatcher(TopicRecorder):
    """rosout lines, to check the exact texts a node logs."""

    def __init__(self):
        super().__init__('/rosout', Log)

    def lines(self, node='/turtlesim', start=0):
        return [(LEVEL_NAMES[log.level], log.msg) for log in self.messages(start) if log.name == node]

    def wait_for_line(self, level, text, start=0, node='/turtlesim', timeout=5.0, whole=True):
        """Wait for a line of that level that is `text` (or, with whole=False, contains it)."""
        def logged():
            return any(line_level == level and (line == text if whole else text in line)
                       for line_level, line in self.lines(node, start))
        return wait_until(logged, timeout, '%s line %r from %s' % (level, text, node))


def published_topics():
    """{topic: type} of every topic that has a publisher."""
    return dict(rosgraph.Master('/turtlesim_test').getPublishedTopics(''))


def graph():
    """(publishers, subscribers, services) as {name: [nodes]}."""
    state = rosgraph.Master('/turtlesim_test').getSystemState()
    return tuple({name: nodes for name, nodes in entries} for entries in state)


def publishes_to(publisher_node, topic, subscriber_node):
    """True once `publisher_node` has a live connection to `subscriber_node` on `topic`."""
    try:
        uri = rosgraph.Master('/turtlesim_test').lookupNode(publisher_node)
        _, _, connections = xmlrpc.client.ServerProxy(uri).getBusInfo('/turtlesim_test')
    except (rosgraph.MasterError, OSError):  # not registered yet, or gone
        return False
    # each connection: [id, other end, direction, transport, topic, connected, ...]
    return any(connection[1] == subscriber_node and connection[2] == 'o' and connection[4] == topic
               for connection in connections)


def twist(linear_x=0.0, angular_z=0.0, linear_y=0.0):
    message = Twist()
    message.linear.x, message.linear.y, message.angular.z = linear_x, linear_y, angular_z
    return message


def connected_publisher(topic, msg_type, timeout=5.0):
    """A publisher that the subscriber of `topic` is already connected to (so no message is lost)."""
    publisher = rospy.Publisher(topic, msg_type, queue_size=10)
    wait_until(lambda: publisher.get_num_connections() > 0, timeout, 'a subscriber on %s' % topic)
    return publisher


def wait_until_still(recorder, timeout=5.0):
    """Wait for a pose with zero velocities (the turtle has stopped) and return it."""
    def still():
        pose = recorder.next_message()
        return None if moving(pose) else pose
    return wait_until(still, timeout, 'the turtle to stop')


def moved(action, recorder, timeout=10.0):
    """Do action() (e.g. publish a command), wait until the turtle moves and stops again; the still pose."""
    action()
    wait_until(lambda: moving(recorder.next_message()), timeout, 'the turtle to move')
    return wait_until_still(recorder, timeout)


def moving(pose):
    return pose.linear_velocity != 0.0 or pose.angular_velocity != 0.0
