"""course_common.sim_record in a ROS node: the record a simulator keeps when the grader names its
file, and who sent a message, told by the master and the connection rather than by the sender.

rospy names a message's sender by the `callerid` of the connection header, which the publisher
fills in as it likes. Here the sender is the node the master has registered at the address this
process connected to (the endpoint the master gave it), and the user that owns the other end of the
socket as the kernel lists it. Unlike the rest of course_common, this module needs rospy."""
import os

import rosgraph
import rospy
import rospy.topics

from course_common.sim_record import ENVIRONMENT, RecordWriter, peer_uid

# The key of the sender in a received message's _connection_header (set after the sender's own
# keys, so that a sender cannot put one there).
SENDER_KEY = '__course_sender'
UNKNOWN = {'nodes': [], 'uid': None, 'label': 'an unknown sender'}
MAX_LOOKUPS = 50   # of the master's node names for one connection


def install(topics=rospy.topics):
    """From now on each message this process receives carries its sender (see sender_of), told
    when the connection's first message comes, while the sender is still there to be asked. Before
    the subscribers are made."""
    subscriber = topics._SubscriberImpl
    if getattr(subscriber.receive_callback, 'names_senders', False):
        return
    receive = subscriber.receive_callback

    def receive_callback(self, messages, connection):
        sender = _SENDERS.of(connection)
        for message in messages:
            header = getattr(message, '_connection_header', None) or {}
            message._connection_header = dict(header, **{SENDER_KEY: sender})
        receive(self, messages, connection)
    receive_callback.names_senders = True
    subscriber.receive_callback = receive_callback


def sender_of(message):
    """Who sent a received message: {'nodes': [registered names], 'uid': N or None, 'label':
    'NODE (uid N)'}; UNKNOWN for one received before install()."""
    return (getattr(message, '_connection_header', None) or {}).get(SENDER_KEY, UNKNOWN)


class Senders:
    """Who is at the other end of a subscriber's connection: the nodes the master has registered at
    the connection's endpoint ('an unregistered node at URI' when none), and the user id the kernel
    gives the other end ('?' without /proc). Each connection is asked once: later messages on it
    come from the same process."""

    def __init__(self):
        self._known = {}   # id(connection): (connection, sender)

    @staticmethod
    def node_names(connection):
        """The nodes the master has registered as publishers of the connection's topic at the
        connection's endpoint, sorted (MAX_LOOKUPS of them looked up at most: a node that registers
        thousands of names must not keep the receiving thread)."""
        endpoint = getattr(connection, 'endpoint_id', None)
        topic = getattr(getattr(connection, 'protocol', None), 'resolved_name', None)
        master = rosgraph.Master(rospy.get_name())
        try:
            publishers = master.getSystemState()[0]
        except OSError:   # the master does not answer
            return []
        names = sorted({node for name, nodes in publishers if name == topic for node in nodes})
        return [name for name in names[:MAX_LOOKUPS] if _uri_of(master, name) == endpoint]

    @staticmethod
    def uid(connection):
        try:
            sock = connection.socket
            return peer_uid(sock.getsockname(), sock.getpeername())
        except (AttributeError, OSError):
            return None

    def of(self, connection):
        known = self._known.get(id(connection))
        if known is None or known[0] is not connection:
            names, uid = self.node_names(connection), self.uid(connection)
            label = ', '.join(names) or 'an unregistered node at %s' % getattr(connection, 'endpoint_id', '?')
            known = (connection, {'nodes': names, 'uid': uid,
                                  'label': '%s (uid %s)' % (label, '?' if uid is None else uid)})
            self._known[id(connection)] = known
        return known[1]


_SENDERS = Senders()


def _uri_of(master, name):
    try:
        return master.lookupNode(name)
    except (OSError, rosgraph.MasterError):
        return None


def open_record():
    """The RecordWriter of the file the grader gave this simulator (COURSE_SIM_RECORD, in the
    trusted side's environment: the student's processes cannot read it), or None."""
    path = os.environ.get(ENVIRONMENT)
    return RecordWriter(path) if path else None
