"""One epoll for every topic: no open file per topic, and each topic sees only its own dead connections."""
import os
import socket
import types

import pytest

from turtlesim import shared_poll
from turtlesim.shared_poll import SharedPoller


def open_files():
    return len(os.listdir('/proc/self/fd'))


@pytest.fixture
def pairs():
    made = []

    def pair():
        ends = socket.socketpair()
        made.extend(ends)
        return ends
    yield pair
    for end in made:
        end.close()


def test_a_thousand_pollers_hold_one_file():
    SharedPoller()
    before = open_files()
    pollers = [SharedPoller() for _ in range(1000)]
    assert open_files() == before
    assert len({id(poller.poller) for poller in pollers}) == 1


def test_each_poller_reports_only_its_own_hung_up_connections(pairs):
    pose, color = SharedPoller(), SharedPoller()
    pose_near, pose_far = pairs()
    color_near, color_far = pairs()
    pose.add_fd(pose_near.fileno())
    color.add_fd(color_near.fileno())
    assert list(pose.error_iter()) == [] and list(color.error_iter()) == []
    color_far.close()  # the subscriber on color went away
    assert list(color.error_iter()) == [color_near.fileno()]
    assert list(pose.error_iter()) == []
    color.remove_fd(color_near.fileno())
    assert list(color.error_iter()) == []


def test_a_number_reused_after_a_close_can_be_added_again(pairs):
    first, second = SharedPoller(), SharedPoller()
    near, _far = pairs()
    first.add_fd(near.fileno())
    second.add_fd(near.fileno())  # still registered: no FileExistsError
    second.remove_fd(near.fileno())


def test_install_replaces_the_poller_class_of_a_module():
    module = types.SimpleNamespace(Poller=object)
    assert shared_poll.install(module)
    assert module.Poller is SharedPoller
    assert not shared_poll.install(types.SimpleNamespace())


def test_rospy_topics_then_hold_no_file_of_their_own():
    """rospy looks the Poller class up when it makes a topic: installed, its topics share the epoll."""
    import rospy.topics as rospy_topics  # only here: the other tests need no ROS
    from std_msgs.msg import Empty
    original = rospy_topics.Poller
    try:
        shared_poll.install(rospy_topics)
        SharedPoller()
        before = open_files()
        impls = [rospy_topics._PublisherImpl('/topic%d' % number, Empty) for number in range(50)]
        assert open_files() == before
        assert all(isinstance(impl.connection_poll, SharedPoller) for impl in impls)
    finally:
        rospy_topics.Poller = original
