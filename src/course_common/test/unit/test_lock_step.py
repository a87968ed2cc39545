"""~lock_step's hold of the simulated clock at each scan (course_common.lock_step, as fake_tb3 uses
it) with the pace of course_common.timing: answered scans go at the factor, unanswered ones at real time at most."""
import threading
import time

from course_common.timing import Pacer, Periodic
from course_common.lock_step import LockStep

SCAN_PERIOD = 0.05   # wall seconds these tests wait at most for an answer
SCAN_NS = int(SCAN_PERIOD * 1e9)


def never():
    return False


def test_only_ticks_after_the_scan_wait():
    lock = LockStep(SCAN_PERIOD)
    assert not lock.holds(10 ** 9)   # no scan sent yet
    lock.sent(SCAN_NS, time.monotonic())
    assert not lock.holds(SCAN_NS) and lock.holds(SCAN_NS + 1)


def test_an_answer_since_the_scan_ends_the_wait_at_once():
    lock = LockStep(10.0)
    lock.sent(SCAN_NS, time.monotonic())
    lock.commanded()
    start = time.monotonic()
    held, ended = lock.await_answer(never)
    assert held == SCAN_NS and ended - start < 5.0 and not lock.holds(2 * SCAN_NS)


def test_a_command_before_the_scan_is_no_answer_to_it():
    lock = LockStep(SCAN_PERIOD)
    lock.commanded()
    sent = time.monotonic()
    lock.sent(SCAN_NS, sent)
    _, ended = lock.await_answer(never)
    assert ended >= sent + SCAN_PERIOD


class JumpingClock:
    """Wall time that can jump ahead: a wait given up without spending it."""

    def __init__(self):
        self.offset = 0.0

    def __call__(self):
        return time.monotonic() + self.offset

    def jump(self, seconds):
        self.offset += seconds


def unanswered(lock, clock, scans):
    """`scans` scans sent whose waits end unanswered (the node is kept from the processor)."""
    for _ in range(scans):
        lock.sent(SCAN_NS, clock())   # (the simulated times play no part here)
        clock.jump(lock.period)
        lock.await_answer(never)


def ends_at_once(lock):
    """Whether the wait for the answer ends well before the (10 s) period of these tests."""
    start = time.monotonic()
    lock.await_answer(never)
    return time.monotonic() - start < 5.0


def test_a_late_answer_is_no_answer_to_the_next_scan():
    lock = LockStep(SCAN_PERIOD, late_answers=5)
    lock.commanded()              # the node has answered before
    lock.sent(SCAN_NS, time.monotonic())
    lock.await_answer(never)      # nothing in time
    sent = time.monotonic()
    lock.sent(2 * SCAN_NS, sent)
    lock.commanded()              # the late answer to the first scan
    _, ended = lock.await_answer(never)
    assert ended >= sent + SCAN_PERIOD


def test_after_its_late_answers_the_answer_to_the_last_scan_ends_the_wait_at_once():
    clock = JumpingClock()
    lock = LockStep(10.0, late_answers=5, clock=clock)
    lock.sent(SCAN_NS, clock())
    lock.commanded()
    lock.await_answer(never)
    unanswered(lock, clock, 2)
    lock.sent(3 * SCAN_NS, clock())
    for _ in range(3):
        lock.commanded()
    assert ends_at_once(lock)


def test_late_answers_that_never_come_are_waited_for_once():
    # A node that answers only the latest scan (a queue of one), after scans it never saw.
    clock = JumpingClock()
    lock = LockStep(SCAN_PERIOD, late_answers=5, clock=clock)
    lock.sent(SCAN_NS, clock())
    lock.commanded()
    lock.await_answer(never)
    unanswered(lock, clock, 7)
    sent = clock()
    lock.sent(9 * SCAN_NS, sent)
    lock.commanded()
    _, ended = lock.await_answer(never)
    assert ended >= sent + SCAN_PERIOD        # the answers it owes might still come
    lock.period = 10.0
    lock.sent(10 * SCAN_NS, clock())
    lock.commanded()
    assert ends_at_once(lock)     # not any more: from then on it is in step


def test_before_any_answer_the_first_one_answers_the_last_scan():
    # The scans a simulator sends before the node has started are owed no answer.
    clock = JumpingClock()
    lock = LockStep(10.0, late_answers=5, clock=clock)
    unanswered(lock, clock, 8)
    lock.sent(9 * SCAN_NS, clock())
    lock.commanded()
    assert ends_at_once(lock)


def test_without_late_answers_any_command_answers_the_last_message():
    # turtlesim's: its nodes also publish at rates of their own.
    clock = JumpingClock()
    lock = LockStep(10.0, clock=clock)
    unanswered(lock, clock, 3)
    lock.sent(4 * SCAN_NS, clock())
    lock.commanded()
    assert ends_at_once(lock)


def test_an_answer_from_another_thread_ends_the_wait():
    lock = LockStep(10.0)
    lock.sent(SCAN_NS, time.monotonic())
    threading.Timer(0.01, lock.commanded).start()
    _, ended = lock.await_answer(never)
    assert ended - time.monotonic() < 5.0 and lock.held_ns is None


def test_shutdown_ends_the_wait():
    lock = LockStep(10.0)
    lock.sent(SCAN_NS, time.monotonic())
    start = time.monotonic()
    lock.await_answer(lambda: True)
    assert time.monotonic() - start < 5.0


def run_ticks(factor, scans, answer):
    """The simulation loop's timing for `scans` scan periods at 10 physics steps a scan: the
    simulated and the wall seconds from the first scan sent to the last."""
    lock = LockStep(SCAN_PERIOD)
    physics, scan = Periodic(10 / SCAN_PERIOD), Periodic(1 / SCAN_PERIOD)
    pacer = Pacer(factor, time.monotonic())
    sent = []   # (simulated, wall) seconds of each scan
    while len(sent) < scans:
        next_ns = min(physics.next_ns, scan.next_ns)
        if lock.holds(next_ns):
            pacer.hold(*lock.await_answer(never))
        due = pacer.due(next_ns)
        now = time.monotonic()
        while now < due:   # the node's way: the clock read once per turn, never a negative sleep
            time.sleep(due - now)
            now = time.monotonic()
        pacer.reached(next_ns, now)
        if physics.next_ns == next_ns:
            physics.advance()
        if scan.next_ns == next_ns:
            lock.sent(next_ns, now)
            sent.append((next_ns / 1e9, now))
            scan.advance()
            if answer:
                lock.commanded()
    return sent[-1][0] - sent[0][0], sent[-1][1] - sent[0][1]


def test_unanswered_scans_run_no_faster_than_real_time():
    simulated, wall = run_ticks(10.0, 6, answer=False)
    assert simulated / wall <= 1.0


def test_answered_scans_run_faster_than_real_time():
    simulated, wall = run_ticks(10.0, 6, answer=True)
    assert simulated / wall > 1.0
