"""Who sent a message (by the master and the connection, not by what the sender says), and who
called a simulator's services, as the simulator tells it (its record in a grading, its latched topic
~service_calls in the course's tests: course_common.service_calls): a node that called a service
the lab does not use (fake_tb3's, turtlesim's teleports and /reset) is named, and the criteria
judged on that run fail."""
from std_msgs.msg import String

from course_common import sim_record_ros
from course_common.service_calls import parse
from course_checks.verdict import Verdict
from course_common.topic_recorder import TopicRecorder


sim_record_ros.install()   # from now on each message received carries its sender


def sender(message):
    """The node that sent a message: the node the master registered at the address this process
    connected to (its name; a sentence naming them, or the address, when several or none), never
    the caller id the sender wrote into its connection header."""
    told = sim_record_ros.sender_of(message)
    return told['nodes'][0] if len(told['nodes']) == 1 else told['label']


class ServiceCallWatch:
    """The simulator's ~service_calls, recorded: only what the simulator itself sent counts."""

    def __init__(self, simulator):
        self.simulator = simulator
        self._recorder = TopicRecorder('%s/service_calls' % simulator, String)

    def _told(self):
        return [message for message in self._recorder.messages() if sender(message) == self.simulator]

    def calls(self):
        """[(service, caller)] as the simulator told them last."""
        told = self._told()
        return parse(told[-1].data) if told else []

    def clear(self):
        self._recorder.clear()

    def close(self):
        self._recorder.close()


def unused(calls, services=None):
    """The calls of the services whose last name is one of `services` (None: every service)."""
    return [(service, caller) for service, caller in calls
            if services is None or service.rsplit('/', 1)[-1] in services]


def called(criterion_ids, calls):
    """Failing verdicts naming who called which service the lab does not use."""
    named = '; '.join('%s called %s' % (caller, service) for service, caller in calls)
    reason = 'not judged: %s, which this lab does not use (as the simulator noted the call)' % named
    return {criterion_id: Verdict(False, reason) for criterion_id in criterion_ids}
