"""Who called a simulator's services, as the simulator tells it on its latched topic
`~service_calls` (std_msgs/String): one line `SERVICE CALLER` for each service called, with the
first node that called it, in the order of the first calls. The grader's checks read it to name a
node that called a service the lab does not use (a teleport, a /reset); the caller is the one
rospy gives in the request's connection header. Pure: the simulators' ROS layer publishes it
(course_common.service_calls_ros)."""
import re

UNPRINTABLE = re.compile(r'[^\x21-\x7e]')   # a caller id is the client's to choose: one word, printable


class ServiceCalls:
    """The services called so far, each with its first caller."""

    def __init__(self):
        self._first_callers = {}   # service: caller, in the order of the first calls

    def note(self, service, caller):
        """A call of `service` by `caller`; True when the service had not been called before (the
        text changed)."""
        if service in self._first_callers:
            return False
        self._first_callers[service] = UNPRINTABLE.sub('?', str(caller)) or '?'
        return True

    def text(self):
        return '\n'.join('%s %s' % item for item in self._first_callers.items())


def parse(text):
    """[(service, caller)] of a ServiceCalls text."""
    return [tuple(line.split(' ', 1)) for line in text.splitlines() if ' ' in line]
