"""Batched writes: bytes leave at the publishing thread's flush, whole and in order, a subscriber
that stops reading loses its oldest messages and holds up nobody, publish() numbers messages."""
import socket
import struct
import types

import pytest

from course_common import batched_writes
from course_common.batched_writes import BatchedConnection, WriterTurns


class Transport:
    """What BatchedConnection uses of a rospy TCPROS transport."""

    def __init__(self, sock):
        self.socket = sock
        self.done = False
        self.stat_bytes = self.stat_num_msg = 0

    def close(self):
        self.done = True


def message(index, size=100):
    body = struct.pack('<I', index) + b'x' * (size - 4)
    return struct.pack('<I', len(body)) + body


def indices(data):
    """The index of each whole message in data (a stream of message())."""
    found, offset = [], 0
    while offset < len(data):
        size = struct.unpack_from('<I', data, offset)[0]
        assert offset + 4 + size <= len(data), 'a message cut short'
        found.append(struct.unpack_from('<I', data, offset + 4)[0])
        offset += 4 + size
    return found


def read_all(sock):
    data = b''
    while True:
        try:
            chunk = sock.recv(1 << 20, socket.MSG_DONTWAIT)
        except BlockingIOError:
            return data
        data += chunk


@pytest.fixture
def pair():
    publisher_side, subscriber_side = socket.socketpair()
    yield publisher_side, subscriber_side
    publisher_side.close()
    subscriber_side.close()


def test_messages_leave_at_the_flush_whole_and_in_order(pair):
    publisher_side, subscriber_side = pair
    connection = BatchedConnection(Transport(publisher_side), queue_size=10)
    for index in range(3):
        connection.write_data(message(index))
    assert read_all(subscriber_side) == b''  # no thread of its own: nothing before the flush
    assert connection.backlog == 3
    WriterTurns().flush()
    assert indices(read_all(subscriber_side)) == [0, 1, 2]
    assert connection.backlog == 0 and connection.stat_num_msg == 3


def test_a_subscriber_that_stops_reading_loses_the_oldest_and_holds_up_nobody(pair):
    publisher_side, subscriber_side = pair
    publisher_side.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    now = [0.0]
    connection = BatchedConnection(Transport(publisher_side), queue_size=10,
                                   clock=lambda: now[0])
    turns = WriterTurns(clock=lambda: now[0])
    total = 3 * batched_writes.MIN_QUEUE
    for index in range(total):
        connection.write_data(message(index))
        if index % 100 == 0:
            turns.flush()  # the socket takes what fits, then no more
    assert connection.backlog == batched_writes.MIN_QUEUE  # the oldest queued were dropped
    now[0] += batched_writes.STALL_SECONDS
    turns.wait_for_subscribers()  # returns: a subscriber that reads nothing is not waited for
    received = read_all(subscriber_side)
    while connection.flush() or connection.backlog:
        received += read_all(subscriber_side)
    received += read_all(subscriber_side)
    seen = indices(received)
    assert seen == sorted(seen) and seen[0] == 0 and seen[-1] == total - 1
    assert seen[-batched_writes.MIN_QUEUE:] == list(range(total - batched_writes.MIN_QUEUE, total))
    assert len(seen) < total


class ClosedTopicTransport(Transport):
    """A transport whose topic rospy's shutdown closed first: telling it fails, as rospy's
    remove_connection does on a closed publisher (its subscriber_listeners are None)."""

    def close(self):
        self.done = True
        self.socket.close()
        raise TypeError("'NoneType' object is not iterable")


@pytest.mark.parametrize('transport_class', [Transport, ClosedTopicTransport])
def test_a_failed_connection_raises_at_the_next_write_and_never_in_the_flushing_thread(pair, transport_class):
    publisher_side, subscriber_side = pair
    transport = transport_class(publisher_side)
    connection = BatchedConnection(transport, queue_size=10)
    subscriber_side.close()
    connection.write_data(message(0))
    WriterTurns().flush()   # the simulator's tick thread: a traceback here ended turtlesim's output
    assert transport.done
    with pytest.raises(OSError):  # rospy's publish() then drops the connection
        connection.write_data(message(1))


class Message:
    _has_header = True

    def __init__(self):
        self.header = types.SimpleNamespace(seq=0)

    def serialize(self, buffer):
        buffer.write(struct.pack('<I', self.header.seq) + b'body')


class Broken:
    def write_data(self, data):
        raise OSError('broken pipe')


def test_publish_numbers_each_message_and_drops_failed_connections(pair):
    publisher_side, subscriber_side = pair
    good = BatchedConnection(Transport(publisher_side), queue_size=10)
    broken = Broken()
    topic = types.SimpleNamespace(connections=[good, broken], closed=False, seq=0,
                                  message_data_sent=0)
    topic.remove_connection = topic.connections.remove
    publisher = types.SimpleNamespace(impl=topic)
    assert batched_writes.subscribed(publisher)
    batched_writes.publish(publisher, Message())
    batched_writes.publish(publisher, Message())
    WriterTurns().flush()
    # As rospy writes them: the length, then the message with its header's seq.
    assert read_all(subscriber_side) == (struct.pack('<II', 8, 1) + b'body'
                                         + struct.pack('<II', 8, 2) + b'body')
    assert topic.connections == [good] and topic.message_data_sent == 24


class PublisherImpl:
    """What batch() uses of rospy's _PublisherImpl: add_connection() wraps a transport in a
    writer-thread connection when queue_size is set."""

    def __init__(self, queue_size):
        self.queue_size = queue_size
        self.connections = []

    def add_connection(self, connection):
        if self.queue_size is not None:
            connection = ('rospy writer thread', connection)
        self.connections.append(connection)


def test_batch_batches_that_publisher_only_with_its_queue_size(pair):
    publisher_side, subscriber_side = pair
    publisher_side.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    batched, other = PublisherImpl(queue_size=5), PublisherImpl(queue_size=5)
    batched_writes.batch(types.SimpleNamespace(impl=batched))
    batched.add_connection(Transport(publisher_side))
    other.add_connection('transport')
    connection = batched.connections[0]
    assert isinstance(connection, BatchedConnection)
    assert other.connections == [('rospy writer thread', 'transport')]
    total = 200
    for index in range(total):
        connection.write_data(message(index, size=1000))
    assert connection.backlog == 5  # its own queue_size, not MIN_QUEUE: a late viewer sees a seq gap
    received = b''
    while connection.flush() or connection.backlog:
        received += read_all(subscriber_side)
    received += read_all(subscriber_side)
    assert indices(received) == list(range(total - 5, total))
