import threading

import pytest
from std_msgs.msg import Int32

from course_testing.recording import TopicRecorder, path_length


def test_path_length_adds_the_sides_of_the_polyline():
    assert path_length([(0, 0), (3, 4), (3, 0)]) == pytest.approx(9.0)
    assert path_length([(0, 0), (2, 0), (2, 2), (0, 2), (0, 0)]) == pytest.approx(8.0)
    assert path_length([(1, 1)]) == 0.0
    assert path_length([]) == 0.0


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
    assert recorder.count() == 0


def test_waiting_for_messages_names_the_topic_when_they_do_not_come(recorder):
    arrive(recorder, 7)
    recorder.wait_for_count(1, 0.1)
    assert recorder.wait_for(lambda message: message.data == 7, 0.1, 'seven').data == 7
    with pytest.raises(AssertionError, match='timed out after 0.1 s waiting for 2 messages on /numbers'):
        recorder.wait_for_count(2, 0.1)
    with pytest.raises(AssertionError, match='a message on /numbers'):
        recorder.next_message(0.1)
