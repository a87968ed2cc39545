"""When turtlesim ticks: every TICK_SECONDS (turtlesim.world) of wall time, as the original, or, with
/use_sim_time, every TICK_SECONDS of a simulated clock that turtlesim itself publishes on /clock and
runs `~real_time_factor` times as fast as the wall clock (so that graders and checks can run the
turtles faster than real time; nodes on simulated time, rospy's and roscpp's Rate included, follow
it). With ~lock_step as well, each tick of that clock also waits for a node's answer (a grader's
closed-loop runs).
"""
import time

import rospy
from rosgraph_msgs.msg import Clock

from course_common.lock_step import LockStep
from course_common.sim_clock import set_own_time, stop_hearing_clock
from course_common.timing import Pacer, Periodic
from turtlesim.world import TICK_SECONDS

TICK_NS = int(round(TICK_SECONDS * 1e9))


class WallTicks:
    """A tick every TICK_SECONDS of the monotonic wall clock; a machine too busy to keep up skips
    the missed ticks, as the original's Qt timer does."""

    simulated = False

    def __init__(self):
        self.next_tick = time.monotonic()

    def wait(self, running):
        """Wait for the next tick (or for running() to turn false); returns its time in seconds."""
        delay = self.next_tick - time.monotonic()
        if delay > 0.0:
            time.sleep(delay)
        elif delay < -TICK_SECONDS:
            self.next_tick = time.monotonic()
        now = self.next_tick
        self.next_tick += TICK_SECONDS
        return now

    def commanded(self):
        """A velocity command came: the wall clock waits for nobody."""


class SimulatedTicks:
    """A tick every TICK_SECONDS of simulated time, which starts at 0 and runs real_time_factor
    times as fast as the wall clock; /clock is published clock_rate times per simulated second,
    and this node's own rospy time is set to it (rospy would otherwise subscribe the node to its
    own /clock).

    With lock_step, the clock runs up to just before each tick and waits there for a velocity
    command sent since the last tick (a closed loop's answer to the pose it was sent) or, failing
    that, until a tick of wall time has passed since the last tick: a node that the machine keeps
    from the processor sees the turtle move on at most as fast as in real time, however fast the
    factor, and one that answers each pose sees the same simulated delays at any factor and load."""

    simulated = True

    def __init__(self, real_time_factor, clock_rate, lock_step=False):
        self.pacer = Pacer(real_time_factor, time.monotonic())
        self.clock = Periodic(clock_rate, 'clock_rate')
        self.clock_pub = rospy.Publisher('/clock', Clock, queue_size=100)
        self.next_tick_ns = 0
        self.lock_step = LockStep(TICK_SECONDS) if lock_step else None
        stop_hearing_clock()
        self._set(0)

    def commanded(self):
        """A velocity command came (any turtle's): with lock_step, the next tick may come."""
        if self.lock_step:
            self.lock_step.commanded()

    def _set(self, sim_ns):
        stamp = rospy.Time(0, sim_ns)
        set_own_time(stamp)
        self.clock_pub.publish(Clock(stamp))

    def _sleep_until(self, sim_ns, running):
        due = self.pacer.due(sim_ns)
        now = time.monotonic()
        while now < due and running():
            time.sleep(min(due - now, 0.05))
            now = time.monotonic()
        self.pacer.reached(sim_ns, now)

    def wait(self, running):
        """Publish /clock up to the next tick, wait for it at the pace; returns its time (s)."""
        tick_ns = self.next_tick_ns
        while self.clock.next_ns < tick_ns and running():
            self._sleep_until(self.clock.next_ns, running)
            self._set(self.clock.next_ns)
            self.clock.advance()
        if self.lock_step and self.lock_step.holds(tick_ns):
            self.lock_step.await_answer(lambda: not running())
        self._sleep_until(tick_ns, running)
        if self.clock.next_ns == tick_ns:
            self.clock.advance()
        if self.lock_step:   # what comes from here on answers this tick's poses
            self.lock_step.sent(tick_ns, time.monotonic())
        self._set(tick_ns)
        self.next_tick_ns += TICK_NS
        return tick_ns / 1e9


def make_ticks(given=None):
    """The ticks the parameters ask for: /use_sim_time, ~real_time_factor, ~clock_rate, ~lock_step;
    or, when `given` (command_line.settings) holds a real_time_factor, the simulated ticks it says,
    whatever the parameters say."""
    given = given or {}
    if 'real_time_factor' in given:
        return SimulatedTicks(given['real_time_factor'], given.get('clock_rate', 250.0), given.get('lock_step', False))
    if not rospy.get_param('/use_sim_time', False):
        return WallTicks()
    factor = rospy.get_param('~real_time_factor', 1.0)
    rate = rospy.get_param('~clock_rate', 250.0)
    lock_step = rospy.get_param('~lock_step', False)
    if not isinstance(lock_step, bool):
        raise ValueError('parameter lock_step must be true or false, got %r' % (lock_step,))
    try:
        factor = float(factor)
    except (TypeError, ValueError):
        raise ValueError('parameter real_time_factor must be a positive number, got %r' % (factor,))
    return SimulatedTicks(factor, rate, lock_step)
