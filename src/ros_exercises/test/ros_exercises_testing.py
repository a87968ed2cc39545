"""What the ros_exercises rostests share: run the commands a student types and save turtlesim's canvas."""
import re

import rospy
from std_srvs.srv import Trigger

from course_testing.processes import ReadPtyProgram
from course_common.waiting import wait_until


class Command:
    """A roslaunch or rosrun command running in a terminal, as a student runs it."""

    def __init__(self, *argv):
        self.program = ReadPtyProgram(list(argv))

    def matches(self, pattern):
        """Every match of the regular expression in what the command printed so far."""
        return re.findall(pattern, self.program.output)

    def wait_for(self, pattern, count=1, timeout=30):
        """Waits until the pattern matched `count` times; returns the matches."""
        return wait_until(lambda: len(self.matches(pattern)) >= count and self.matches(pattern), timeout,
                          what='%d lines matching %r from %s' % (count, pattern, ' '.join(self.program.process.args)),
                          poll=0.1)

    def stop(self, timeout=20):
        """Ctrl-C, then the exit code once everything it started has stopped."""
        return self.program.stop(timeout)


def save_canvas(path):
    """Has turtlesim write its canvas to `path` (a PNG); returns the path it reports."""
    rospy.set_param('/turtlesim/canvas_png', str(path))
    rospy.wait_for_service('/turtlesim/save_canvas', 10)
    response = rospy.ServiceProxy('/turtlesim/save_canvas', Trigger)()
    if not response.success:
        raise AssertionError('turtlesim could not save its canvas: %s' % response.message)
    return response.message
