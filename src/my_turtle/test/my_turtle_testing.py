"""Helpers for the my_turtle rostests: record turtle1's poses, run a node and keep what it prints."""
import re

from course_checks.turtle import turtle_poses
from course_testing.processes import ReadPtyProgram
from course_common.waiting import wait_until

# A pose line as the slide shows it, e.g. "[ INFO] [1513815819.814175430]: x: 8.46, y: 5.54"
POSE_LINE = r'^\[ INFO\] \[\d+\.\d+\]: x: (\d+\.\d\d), y: (\d+\.\d\d)$'
# rosconsole wraps every line in colour codes (ESC[0m for INFO), which a terminal does not show.
COLOUR_CODE = re.compile(r'\x1b\[[0-9;]*m')


def turtle1_poses():
    """A recorder of turtle1's poses, once the first has arrived."""
    recorder = turtle_poses('turtle1')
    recorder.wait_for_count(1, 30)
    return recorder


class PrintingNode(ReadPtyProgram):
    """A node started with rosrun, printing into a pseudo-terminal as it would into a terminal
    (into a pipe rosconsole would hold lines back in its buffer)."""

    def __init__(self, package, executable):
        super().__init__(['rosrun', package, executable])

    @property
    def lines(self):
        """The complete lines printed so far, as a terminal shows them."""
        return [COLOUR_CODE.sub('', line) for line in self.output.split('\r\n')[:-1]]

    def wait_for_line(self, text, timeout):
        return wait_until(lambda: any(text in line for line in self.lines), timeout,
                          'the node to print %r' % text)


def hold_key(terminal, key, condition, timeout, what):
    """Keep `key` pressed in a PtyProgram (it repeats every 50 ms, as a held key does) until
    condition() holds."""
    def pressed_until():
        terminal.type(key)
        terminal.read_available(0.05)
        return condition()
    return wait_until(pressed_until, timeout, what)
