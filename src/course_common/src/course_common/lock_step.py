"""The simulators' ~lock_step (fake_tb3 after each scan, turtlesim after each tick's poses): simulated
time stands at the time of what was sent until a velocity command has come since (a node's answer
to it), or until a period of wall time has passed since the tick that sent it.

A node that answers each message therefore sees the robot move the same simulated distances at any
real-time factor and however long the machine keeps it from the processor: its answer is applied
from the next step, as on a robot whose node answers within a step. While nobody answers, a period
of simulated time costs at least a period of wall time (the wait, then the rest of the period at
the factor): the clock runs no faster than real time. A node that publishes commands all the time
never makes the clock wait, which is only the clock without lock step. Any robot's command answers
(the graders run one robot).

A node kept from the processor longer than a period answers late, and its messages queue up
meanwhile: with late_answers, its late answers are counted off before a command answers the
message just sent, so it is not one message behind from then on (each of its answers would move
the robot one scan later than it should). Pure: no rospy.
"""
import threading
import time

# Wall seconds between two looks at shutdown while waiting.
POLL_SECONDS = 0.05


class LockStep:
    """The hold of the simulated clock at the last message sent that a node answers, for the
    simulation thread; commanded() may be called from any thread. period: seconds of wall time
    waited at most for an answer. late_answers: how many unanswered messages a node kept from the
    processor may still answer late, in a burst, before it answers the last one (fake_tb3: a
    node that answers each scan, whose scans queue up meanwhile); 0: any command answers the
    last message (turtlesim, whose nodes also publish at rates of their own)."""

    def __init__(self, period, late_answers=0, clock=time.monotonic):
        self.period = period
        self.late_answers = late_answers
        self.clock = clock
        self._changed = threading.Condition()
        self._owed = 0        # answers still to come: to what was sent, and late ones before it
        self._came = False    # a command came since the last message was sent
        self._heard = False   # any command came yet: before, nobody answers, and nobody is late
        self.held_ns = None   # the time of what awaits its answer, None when nothing is held
        self._give_up = 0.0

    def commanded(self):
        """A velocity command came."""
        with self._changed:
            self._owed = max(self._owed - 1, 0)
            self._came = self._heard = True
            self._changed.notify()

    def sent(self, sim_ns, wall):
        """The tick at simulated time sim_ns (wall time `wall`) sent what a node answers (a scan,
        a pose), before it goes out to the subscribers: what comes from now on answers it, after
        the late answers still owed to earlier ones."""
        with self._changed:
            self._owed = min(self._owed + 1, self.late_answers + 1) if self._heard else 1
            self._came = False
            self.held_ns = sim_ns
            self._give_up = wall + self.period

    def holds(self, sim_ns):
        """Whether a tick at sim_ns must first wait for the answer (it is later than what was sent)."""
        return self.held_ns is not None and sim_ns > self.held_ns

    def await_answer(self, shutdown):
        """Wait for the answer, at most until a period of wall time has passed since the tick
        that sent it, or shutdown() is true; then let time go on. Returns (the simulated time that
        was held, the wall time the wait ended)."""
        with self._changed:
            now = self.clock()
            while self._owed and now < self._give_up and not shutdown():
                self._changed.wait(min(self._give_up - now, POLL_SECONDS))
                now = self.clock()
            if self._came:
                # The node answers, but fewer times than it was sent messages (it dropped some from
                # a short queue): what it still owes would never come.
                self._owed = 0
            held, self.held_ns = self.held_ns, None
        return held, self.clock()
