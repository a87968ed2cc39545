import threading

import pytest
from std_msgs.msg import Int32

from course_common import topic_recorder
from course_common.topic_recorder import TopicRecorder


def arrive(recorder, *numbers):
    """As rospy would deliver them, from its own thread."""
    thread = threading.Thread(target=lambda: [recorder._keep(Int32(number)) for number in numbers])
    thread.start()
    thread.join()


@pytest.fixture
def recorder():
    # rospy registers a subscriber with the master only once a node exists: none here.
    recorder = TopicRecorder('/numbers', Int32)
    yield recorder
    recorder.close()


def test_the_recorder_keeps_every_message_in_order_with_its_arrival(recorder):
    assert recorder.latest() is None and recorder.count() == 0
    arrive(recorder, 1, 2, 3)
    assert [message.data for message in recorder.messages()] == [1, 2, 3]
    assert [message.data for message in recorder.messages(1)] == [2, 3]
    arrivals = [arrival for arrival, _ in recorder.entries()]
    assert arrivals == sorted(arrivals)
    assert recorder.latest().data == 3
    assert [message.data for _, message in recorder.arrived_since(arrivals[1])] == [2, 3]
    recorder.clear()
    assert recorder.count() == 0 and recorder.latest() is None


def test_past_its_bound_the_recorder_drops_the_older_half_and_counts_on(recorder, monkeypatch):
    monkeypatch.setattr(topic_recorder, 'MAX_MESSAGES', 4)
    arrive(recorder, 1, 2, 3, 4, 5)
    assert recorder.count() == 5
    assert [message.data for message in recorder.messages()] == [3, 4, 5]
    assert [message.data for message in recorder.messages(3)] == [4, 5]
    assert [message.data for message in recorder.messages(1)] == [3, 4, 5]
    recorder.clear()
    arrive(recorder, 6)
    assert recorder.count() == 1 and [message.data for message in recorder.messages()] == [6]


def test_waiting_for_messages_names_the_topic_when_they_do_not_come(recorder):
    arrive(recorder, 7)
    recorder.wait_for_count(1, 0.1)
    assert recorder.wait_for(lambda message: message.data == 7, 0.1, 'seven').data == 7
    with pytest.raises(AssertionError, match='timed out after 0.1 s waiting for 2 messages on /numbers'):
        recorder.wait_for_count(2, 0.1)
    with pytest.raises(AssertionError, match='a message on /numbers'):
        recorder.next_message(0.1)
