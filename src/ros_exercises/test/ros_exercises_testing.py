"""What the ros_exercises rostests share: run the commands a student types and save turtlesim's canvas."""
import re
import subprocess
import threading

import rospy
from std_srvs.srv import Trigger

from course_testing.processes import PtyProgram, stop_process_group
from course_testing.waiting import wait_until


class Command:
    """A roslaunch or rosrun command running in a terminal, as a student runs it.

    A thread reads its output all the time: a node that cannot write its log lines would stall.
    """

    def __init__(self, *argv):
        self.program = PtyProgram(list(argv))
        self._reading = True
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        while self._reading:
            self.program.read_available(0.05)

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
        stop_process_group(self.program.process, timeout)
        self._reading = False
        self._reader.join()
        return self.program.stop()


def run(*argv, timeout=30):
    """Runs a command to its end; returns its exit code and everything it printed."""
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                            timeout=timeout)
    return result.returncode, result.stdout


def save_canvas(path):
    """Has turtlesim write its canvas to `path` (a PNG); returns the path it reports."""
    rospy.set_param('/turtlesim/canvas_png', str(path))
    rospy.wait_for_service('/turtlesim/save_canvas', 10)
    response = rospy.ServiceProxy('/turtlesim/save_canvas', Trigger)()
    if not response.success:
        raise AssertionError('turtlesim could not save its canvas: %s' % response.message)
    return response.message
