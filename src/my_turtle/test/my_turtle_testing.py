"""Helpers for the my_turtle rostests: record turtle1's poses, run a node and keep what it prints."""
import math
import re
import threading

from turtlesim.msg import Pose

from course_testing.processes import PtyProgram
from course_testing.recording import TopicRecorder, path_length
from course_testing.waiting import wait_until

POSE_RATE_HZ = 62.5  # turtlesim publishes the pose at every 16 ms tick
TICK_SECONDS = 0.016
# A pose line as the slide shows it, e.g. "[ INFO] [1513815819.814175430]: x: 8.46, y: 5.54"
POSE_LINE = r'^\[ INFO\] \[\d+\.\d+\]: x: (\d+\.\d\d), y: (\d+\.\d\d)$'
# rosconsole wraps every line in colour codes (ESC[0m for INFO), which a terminal does not show.
COLOUR_CODE = re.compile(r'\x1b\[[0-9;]*m')


def turtle1_poses():
    """A recorder of turtle1's poses, once the first has arrived."""
    recorder = TopicRecorder('/turtle1/pose', Pose)
    recorder.wait_for_count(1, 30)
    return recorder


def travelled(samples):
    """Distance travelled along recorded (time, pose) entries, in metres."""
    return path_length([(pose.x, pose.y) for _, pose in samples])


def per_tick(samples):
    """(distance, heading change) of one turtlesim tick, the median over consecutive poses: the
    turtle's speed in turtlesim's own time (a fixed 16 ms a tick), which a busy machine that delays
    the ticks does not change, and a pose lost on the way does not skew."""
    steps = sorted(math.hypot(b.x - a.x, b.y - a.y) for (_, a), (_, b) in zip(samples, samples[1:]))
    turns = sorted(math.remainder(b.theta - a.theta, 2 * math.pi) for (_, a), (_, b) in zip(samples, samples[1:]))
    return steps[len(steps) // 2], turns[len(turns) // 2]


def tick_speeds(samples):
    """(linear m/s, angular rad/s) of the turtle in turtlesim's time, from per_tick."""
    step, turn = per_tick(samples)
    return step / TICK_SECONDS, turn / TICK_SECONDS


def duration(samples):
    return samples[-1][0] - samples[0][0]


def turned(samples):
    """Heading change along the recorded poses in radians (counter-clockwise positive, unwrapped)."""
    return sum(math.remainder(b.theta - a.theta, 2 * math.pi)
               for (_, a), (_, b) in zip(samples, samples[1:]))


class PrintingNode(PtyProgram):
    """A node started with rosrun, printing into a pseudo-terminal as it would into a terminal
    (into a pipe rosconsole would hold lines back in its buffer). A thread keeps reading, or the
    node would block once the terminal's buffer is full."""

    def __init__(self, package, executable):
        super().__init__(['rosrun', package, executable])
        self._draining = True
        self._drain_thread = threading.Thread(target=self._drain, daemon=True)
        self._drain_thread.start()

    def _drain(self):
        while self._draining:
            self.read_available(0.05)

    @property
    def lines(self):
        """The complete lines printed so far, as a terminal shows them."""
        return [COLOUR_CODE.sub('', line) for line in self.output.split('\r\n')[:-1]]

    def wait_for_line(self, text, timeout):
        return wait_until(lambda: any(text in line for line in self.lines), timeout,
                          'the node to print %r' % text)

    def stop(self, timeout=10):
        """Ctrl-C, as in the terminal; returns the exit status."""
        self._draining = False
        self._drain_thread.join()
        return super().stop(timeout)


def hold_key(terminal, key, condition, timeout, what):
    """Keep `key` pressed in a PtyProgram (it repeats every 50 ms, as a held key does) until
    condition() holds."""
    def pressed_until():
        terminal.type(key)
        terminal.read_available(0.05)
        return condition()
    return wait_until(pressed_until, timeout, what)
