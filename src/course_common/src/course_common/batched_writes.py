"""Publishing many messages a second from rospy: each subscriber's messages written in batches.

rospy gives every connection of a publisher with a queue_size a QueuedConnection: publish() queues
the bytes, wakes the connection's writer thread and calls time.sleep(0), so that every message
costs a hand-over of the interpreter lock to that thread and back, and a send of its own. A
simulator publishing thousands of messages a second (fake_tb3 faster than real time) spent most of
its time there. BatchedConnection has QueuedConnection's interface; publish() only appends the
bytes, and the writer thread sends everything queued since its last turn in one write, whenever it
gets the interpreter lock (the publishing thread lets it, see yield_to_writers()).

Nothing on the wire changes (the same bytes in the same order). A publisher faster than real time
can outrun its subscribers: WriterTurns.wait_for_subscribers() then holds the publishing thread
until they have caught up, so that a subscriber that keeps reading gets every message, however
fast the simulation is asked to run. A subscriber that stops reading is waited for at most
STALL_SECONDS; then it loses the oldest of its messages, as with rospy, and holds up nobody (its
queue holds at least MIN_QUEUE messages, more than the publisher's queue_size, so that a burst
between two turns of the writer is not cut).
"""
import threading
import time
import weakref

MIN_QUEUE = 1000  # messages a connection may hold before the oldest are dropped
BACKLOG = 100  # messages waiting for one subscriber beyond which the publisher waits for it
STALL_SECONDS = 1.0  # a subscriber that reads nothing for this long is no longer waited for
CHUNK = 16384  # bytes per socket write
_LIVE = weakref.WeakSet()  # the BatchedConnections of this process


class BatchedConnection:
    """rospy.impl.tcpros_pubsub.QueuedConnection's interface over a connection (a rospy Transport),
    with batched writes."""

    def __init__(self, connection, queue_size):
        self._connection = connection
        self._queue_size = max(queue_size, MIN_QUEUE) if queue_size > 0 else 0
        self._lock = threading.Lock()
        self._data_available = threading.Condition(self._lock)
        self._queue = []
        self._error = None
        self.progress_at = None  # while writing: time.monotonic() the socket last took a chunk
        connection.set_cleanup_callback(self._closed)
        self._thread = threading.Thread(target=self._run, daemon=True,
                                        name='batched-writer %s' % getattr(connection, 'endpoint_id', ''))
        self._thread.start()
        _LIVE.add(self)

    @property
    def backlog(self):
        """Messages queued and not yet handed to the socket."""
        return len(self._queue)

    def _closed(self, _connection):
        with self._lock:
            self._data_available.notify()

    def __getattr__(self, name):
        if name.startswith('__'):
            raise AttributeError(name)
        return getattr(self._connection, name)

    def write_data(self, data):
        with self._lock:
            if self._error is not None:  # the writer thread failed: rospy drops this connection
                error, self._error = self._error, None
                raise error
            self._queue.append(data)
            if self._queue_size and len(self._queue) > self._queue_size:
                del self._queue[0]
            if len(self._queue) == 1:
                self._data_available.notify()
        return True

    def _run(self):
        while not self._connection.done:
            with self._lock:
                while not self._queue and not self._connection.done:
                    self._data_available.wait()
                batch, self._queue = self._queue, []
            if not batch:
                continue
            data = memoryview(batch[0] if len(batch) == 1 else b''.join(batch))
            try:
                for start in range(0, len(data), CHUNK):  # a slow reader still shows progress
                    self.progress_at = time.monotonic()
                    self._connection.write_data(data[start:start + CHUNK])
            except Exception as error:  # as rospy: raised by the next write_data, which drops us
                with self._lock:
                    self._error = error
            finally:
                self.progress_at = None


def install(topics_module):
    """Make rospy (its module rospy.topics) wrap publisher connections in BatchedConnection; only
    connections made after this call are batched."""
    topics_module.QueuedConnection = BatchedConnection


class WriterTurns:
    """Lets rospy's writer threads run at least every `period` wall seconds while the calling
    thread computes flat out (Python hands its lock over only when a thread waits, or every 5 ms:
    at 100x real time, half a simulated second of messages), and waits for subscribers that fall
    more than BACKLOG messages behind."""

    def __init__(self, period=0.001, clock=time.monotonic, connections=_LIVE):
        self.period = period
        self._clock = clock
        self._connections = connections
        self._last = clock()

    def maybe_yield(self):
        now = self._clock()
        if now - self._last >= self.period:
            time.sleep(0)
            self.wait_for_subscribers()
            self._last = self._clock()

    def wait_for_subscribers(self, poll=0.0005):
        """Sleep while a subscriber that is still reading has more than BACKLOG messages queued
        (one whose socket has taken nothing for STALL_SECONDS is not reading)."""
        while True:
            now = self._clock()
            behind = [connection for connection in list(self._connections)
                      if connection.backlog > BACKLOG and not connection.done
                      and now - (connection.progress_at or now) < STALL_SECONDS]
            if not behind:
                return
            time.sleep(poll)
