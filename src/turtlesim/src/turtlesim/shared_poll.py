"""One epoll for all the topics of a process, in place of rospy's one per topic.

rospy gives every topic (each publisher and subscriber name) a Poller holding its own epoll file,
used only to notice dead connections when a new one arrives. That file is not closed when the topic
is unregistered: the Poller refers to itself (its methods are stored on it), so it lives until
Python's cycle collector happens to run. A turtle has three topics, so a node making turtles runs out
of files at about a third of `ulimit -n`. SharedPoller has rospy's Poller interface (add_fd,
remove_fd, error_iter) over one epoll shared by every topic: a topic holds no file of its own, and
each topic still sees only the errors of its own connections.
"""
import select
import threading

_ERRORS = select.EPOLLHUP | select.EPOLLERR | select.EPOLLRDHUP if hasattr(select, 'epoll') else 0


class SharedPoller:
    """rospy.topics.Poller's interface; every instance uses the same epoll (made on first use)."""

    _epoll = None
    _epoll_lock = threading.Lock()

    @classmethod
    def _shared(cls):
        with cls._epoll_lock:
            if cls._epoll is None or cls._epoll.closed:
                cls._epoll = select.epoll()
            return cls._epoll

    def __init__(self):
        self.poller = self._shared()
        self._fds = set()  # the file descriptors of this topic's connections

    def add_fd(self, fd):
        try:
            self.poller.register(fd, _ERRORS)
        except FileExistsError:  # still registered under a number reused since: watch it for this topic
            self.poller.modify(fd, _ERRORS)
        self._fds.add(fd)

    def remove_fd(self, fd):
        self._fds.discard(fd)
        self.poller.unregister(fd)

    def error_iter(self):
        """The descriptors of this topic's connections that hung up or failed."""
        mine = set(self._fds)
        for fd, event in self.poller.poll(0):
            if fd in mine and event & _ERRORS:
                yield fd


def install(topics_module):
    """Make rospy (its module rospy.topics) build SharedPollers; True if done (Linux has epoll)."""
    if not hasattr(select, 'epoll') or not hasattr(topics_module, 'Poller'):
        return False
    topics_module.Poller = SharedPoller
    return True
