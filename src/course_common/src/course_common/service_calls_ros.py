"""The simulators' topic `~service_calls` (course_common.service_calls says what it carries); this
module, unlike the rest of course_common, needs rospy."""
import threading

import rospy
from std_msgs.msg import String

from course_common.service_calls import ServiceCalls


class ServiceCallTopic:
    """~service_calls of this node, latched, empty until a service of the node is called; each
    call also given to note('service_call', service=..., caller=...) when there is one (the
    simulator's record for the grader: course_common.sim_record)."""

    def __init__(self, note=None):
        self._note = note
        self._calls = ServiceCalls()
        self._lock = threading.Lock()
        self._publisher = rospy.Publisher('~service_calls', String, queue_size=1, latch=True)
        self._publisher.publish(String(''))

    def noted(self, service, handler):
        """`handler` of the service named `service` (as given to rospy.Service), each call noted
        with its caller before it runs."""
        resolved = rospy.resolve_name(service)

        def handle(request):
            caller = getattr(request, '_connection_header', {}).get('callerid', '?')
            if self._note:
                self._note('service_call', service=resolved, caller=caller)
            with self._lock:
                if self._calls.note(resolved, caller):
                    self._publisher.publish(String(self._calls.text()))
            return handler(request)
        return handle
