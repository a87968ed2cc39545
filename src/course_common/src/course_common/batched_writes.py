"""Publishing many messages a second from rospy: every subscriber's messages written in batches,
by the publishing thread, with no thread per subscriber.

rospy gives every connection of a publisher with a queue_size a QueuedConnection: a writer thread
of its own, and a publish() that queues the bytes, wakes that thread and calls time.sleep(0), so
that every message costs a hand-over of the interpreter lock to that thread and back, and a send of
its own. A simulator publishing thousands of messages a second spent most of its time there (and
fake_tb3 with 30 robots ran 120 such threads, each woken for about one message per tick).

BatchedConnection has QueuedConnection's interface and no thread: write_data() only appends the
bytes. The publishing thread calls WriterTurns.flush() once per turn (a tick, or every `period`
while it runs flat out): each connection with something queued hands all of it to its socket in
one non-blocking send, and keeps what the socket does not take for the next turn. publish() gives
a message to a publisher's connections as rospy's publish() does (the same sequence numbers and
bytes) without its locking and copying per message.

Nothing on the wire changes (the same bytes in the same order). A publisher faster than real time
can outrun its subscribers: WriterTurns.wait_for_subscribers() then holds the publishing thread
until they have caught up, so that a subscriber that keeps reading gets every message, however
fast the simulation is asked to run. A subscriber that stops reading is waited for at most
STALL_SECONDS; then it loses the oldest of its messages, as with rospy, and holds up nobody (its
queue holds at least MIN_QUEUE messages, more than the publisher's queue_size, so that a burst
between two turns is not cut).

A process that install()s this must flush regularly (every connection of the process is batched,
/rosout's too); between two flushes, messages wait. batch() batches one publisher only, for a
thread that publishes at most one message per turn on it and leaves the node's other topics to
rospy.
"""
import io
import socket
import struct
import threading
import time

MIN_QUEUE = 1000  # messages a connection may hold before the oldest are dropped
BACKLOG = 100  # messages waiting for one subscriber beyond which the publisher waits for it
STALL_SECONDS = 1.0  # a subscriber that reads nothing for this long is no longer waited for
_LENGTH = struct.Struct('<I')
_PENDING = set()  # the BatchedConnections with bytes not yet handed to their socket


class BatchedConnection:
    """rospy.impl.tcpros_pubsub.QueuedConnection's interface over a connection (a rospy TCPROS
    transport), with its writes batched by flush()."""

    def __init__(self, connection, queue_size, clock=time.monotonic, min_queue=MIN_QUEUE):
        self._connection = connection
        self._queue_size = max(queue_size, min_queue) if queue_size > 0 else 0
        self._lock = threading.Lock()
        self._queue = []  # whole messages, none of their bytes sent yet
        self._unsent = b''  # the rest of the batch the socket took only part of
        self._error = None
        self._clock = clock
        self.progress_at = clock()  # when the socket last took bytes, or had none waiting

    @property
    def backlog(self):
        """Messages queued and not yet handed to the socket."""
        return len(self._queue)

    def __getattr__(self, name):
        if name.startswith('__'):
            raise AttributeError(name)
        return getattr(self._connection, name)

    def write_data(self, data):
        with self._lock:
            if self._error is not None:  # the socket failed: rospy drops this connection
                error, self._error = self._error, None
                raise error
            self._queue.append(data)
            if self._queue_size and len(self._queue) > self._queue_size:
                del self._queue[0]
        _PENDING.add(self)
        return True

    def flush(self):
        """Hand what is queued to the socket, as far as it takes it without waiting; returns
        whether bytes are left for a later flush."""
        connection = self._connection
        while not connection.done and self._error is None:
            if not self._unsent:
                with self._lock:
                    batch, self._queue = self._queue, []
                if not batch:
                    self.progress_at = self._clock()
                    return False
                self._unsent = memoryview(batch[0] if len(batch) == 1 else b''.join(batch))
                connection.stat_num_msg += len(batch)
            try:
                sent = connection.socket.send(self._unsent, socket.MSG_DONTWAIT)
            except BlockingIOError:
                return True
            except OSError as error:  # as rospy: raised by the next write_data, which drops us
                self._error = error
                try:
                    connection.close()   # closes the socket, then tells the topic
                except Exception:  # noqa: BLE001  the topic, closed by rospy's shutdown meanwhile, fails
                    pass           # to forget a connection (its listeners are None): nothing is left open
                return False
            connection.stat_bytes += sent
            self._unsent = self._unsent[sent:]
            self.progress_at = self._clock()
            if self._unsent:
                return True
        return False


def install(topics_module):
    """Make rospy (its module rospy.topics) wrap publisher connections in BatchedConnection; only
    connections made after this call are batched."""
    topics_module.QueuedConnection = BatchedConnection


def batch(publisher):
    """Batch the connections of this publisher only (those made after this call), each keeping its
    queue_size (a publisher of at most one message per turn needs no more); the process's other
    topics keep rospy's writer threads. Publish with publish() and flush from the same thread."""
    topic = publisher.impl
    queue_size, topic.queue_size = topic.queue_size or 0, None  # None: rospy wraps nothing itself
    add_connection = topic.add_connection
    topic.add_connection = lambda connection: add_connection(
        BatchedConnection(connection, queue_size, min_queue=1))


def publish(publisher, message):
    """publisher.publish(message) for a publisher that is not latched, from the thread that
    flushes: the same sequence number and bytes to each connection, without rospy's lock, buffer
    and copies per message. Connections that failed are dropped, as rospy does."""
    topic = publisher.impl
    connections = topic.connections
    if topic.closed or not connections:
        return
    topic.seq += 1
    if getattr(message, '_has_header', False):
        message.header.seq = topic.seq
    buffer = io.BytesIO()
    buffer.write(b'\0\0\0\0')  # the length, once known
    message.serialize(buffer)
    size = buffer.tell() - 4
    buffer.seek(0)
    buffer.write(_LENGTH.pack(size))
    data = buffer.getvalue()
    for connection in connections:
        try:
            connection.write_data(data)
        except Exception:  # as rospy: a connection that failed is dropped
            topic.remove_connection(connection)
    topic.message_data_sent += len(data)


def subscribed(publisher):
    """Whether publisher has a subscriber (get_num_connections() without its lock)."""
    topic = publisher.impl
    return topic is not None and bool(topic.connections)


class WriterTurns:
    """Sends what the publishing thread has queued: at each flush(), and every `period` wall
    seconds of maybe_flush() while it computes flat out; waits for subscribers that fall more than
    BACKLOG messages behind."""

    def __init__(self, period=0.01, clock=time.monotonic):
        self.period = period
        self._clock = clock
        self._last = clock()

    def maybe_flush(self):
        if self._clock() - self._last >= self.period:
            self.flush()
            self.wait_for_subscribers()

    def flush(self):
        for connection in list(_PENDING):
            _PENDING.discard(connection)
            if connection.flush():
                _PENDING.add(connection)
        self._last = self._clock()

    def wait_for_subscribers(self, poll=0.0005):
        """Sleep and flush while a subscriber that is still reading has more than BACKLOG
        messages queued (one whose socket has taken nothing for STALL_SECONDS is not reading)."""
        while True:
            now = self._clock()
            behind = [connection for connection in list(_PENDING)
                      if connection.backlog > BACKLOG and not connection.done
                      and now - connection.progress_at < STALL_SECONDS]
            if not behind:
                return
            time.sleep(poll)
            self.flush()
