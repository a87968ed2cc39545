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
        while time.monotonic() < due:
            time.sleep(due - time.monotonic())
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
