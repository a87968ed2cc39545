"""What the simulators of a grading recorded of themselves (course_common.sim_record), read as the
checks read a topic: the evidence of a run is what the simulator did, never a message a node sent.
And the nodes that publish on a simulator's topics all the same, as the master lists them."""
import threading
import time

import rosgraph
import rospy

from course_common.service_calls import ServiceCalls, parse
from course_common.sim_record import RecordReader
from course_common.waiting import wait_for

# Wall seconds between two looks at the master for other publishers on a simulator's topics.
PUBLISHER_LOOK_SECONDS = 0.1


class PublisherLook:
    """Nodes other than `owners` that the master lists as publishers of `topics`, looked at every
    PUBLISHER_LOOK_SECONDS on a thread of its own until close(), and at each look(): {topic without
    its first /: nodes}. What they sent never counts; they are named."""

    def __init__(self, topics=(), owners=()):
        self.topics = set(topics)   # more may be added (watched) while it looks
        self.owners = set(owners)
        self.found = {}
        self._looked = 0.0
        self._lock = threading.Lock()
        self._closed = threading.Event()
        threading.Thread(target=self._look_until_closed, name='publisher-look', daemon=True).start()

    def _look_until_closed(self):
        while not self._closed.wait(PUBLISHER_LOOK_SECONDS):
            self.look()

    def close(self):
        self._closed.set()

    def look(self, at_most_every=PUBLISHER_LOOK_SECONDS / 2):
        """{topic: nodes} found so far, after a look at the master (unless one was just made)."""
        with self._lock:
            if time.monotonic() - self._looked >= at_most_every:
                self._looked = time.monotonic()
                self._look()
            return {topic: set(nodes) for topic, nodes in self.found.items()}

    def _look(self):
        try:
            publishers = rosgraph.Master(rospy.get_name()).getSystemState()[0]
        except OSError:   # the master does not answer: what was found stays
            return
        for topic, nodes in publishers:
            others = set(nodes) - self.owners
            if topic in self.topics and others:
                self.found.setdefault(topic.lstrip('/'), set()).update(others)


class Records:
    """The entries of some simulators' records (one file each), read as they come, kept by name."""

    def __init__(self, paths=()):
        self._readers = [RecordReader(path) for path in paths]
        self._lock = threading.Lock()
        self._by_name = {}

    def add(self, path):
        """One more simulator's record (one started later in the run)."""
        with self._lock:
            self._readers.append(RecordReader(path))

    def entries(self, name):
        """[Entry] named `name` so far, in the order written (each record's after the other's)."""
        with self._lock:
            for reader in self._readers:
                for entry in reader.read_new():
                    self._by_name.setdefault(entry.name, []).append(entry)
            return list(self._by_name.get(name, []))

    def events(self, name):
        """The fields of the events named `name` so far."""
        return [entry.fields() for entry in self.entries(name)]

    def service_calls(self):
        """[(service, caller as the caller says)]: each service the simulators noted a call of, with
        its first caller, in the order of the first calls."""
        calls = ServiceCalls()
        for call in self.events('service_call'):
            calls.note(call['service'], call['caller'])
        return parse(calls.text())


class RecordedTopic:
    """One topic as the simulator recorded what it published on it, with the calls the checks make
    of a course_common.topic_recorder.TopicRecorder: (wall time the simulator sent it, message)."""

    def __init__(self, records, topic, message_class):
        self.records = records
        self.topic = topic
        self.message_class = message_class
        self._decoded = []

    def entries(self, start=0):
        new = self.records.entries(self.topic)[len(self._decoded):]
        self._decoded += [(entry.wall, self.message_class().deserialize(entry.payload)) for entry in new]
        return self._decoded[start:]

    def messages(self, start=0):
        return [message for _, message in self.entries(start)]

    def count(self):
        return len(self.entries())

    def latest(self):
        entries = self.entries()
        return entries[-1][1] if entries else None

    def record(self, seconds):
        """(wall time, message) of the messages sent over the next `seconds` (from the first sent
        after this call); what came by a time-out of seconds + 10."""
        first = self.count()

        def long_enough():
            entries = self.entries(first)
            return len(entries) > 1 and entries[-1][0] - entries[0][0] >= seconds
        wait_for(long_enough, seconds + 10)
        return self.entries(first)

    def close(self):
        """Nothing to give back: for the callers of a TopicRecorder."""
