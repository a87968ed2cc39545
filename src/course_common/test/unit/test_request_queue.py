"""The simulators' request queue: order, results, refusals, waiting callers, shutdown."""
import threading

import pytest

from course_common.request_queue import RequestQueue, Stopped


class Refused(ValueError):
    pass


def test_actions_run_in_order_with_the_tick_arguments():
    queue = RequestQueue()
    ran = []
    queue.submit(lambda now: ran.append(('a', now)))
    queue.submit(lambda now: ran.append(('b', now)))
    assert ran == [] and len(queue) == 2
    queue.run_pending(1.5)
    assert ran == [('a', 1.5), ('b', 1.5)] and len(queue) == 0


def test_a_caller_waits_for_the_simulation_thread_and_gets_the_result_or_the_refusal():
    queue = RequestQueue(expected=(Refused,))
    stop = threading.Event()

    def simulation_thread():
        while not stop.wait(0.001):
            queue.run_pending()
    thread = threading.Thread(target=simulation_thread)
    thread.start()
    try:
        assert queue.call(lambda: 42, stopped=lambda: False) == 42
        with pytest.raises(Refused, match='no such turtle'):
            queue.call(lambda: (_ for _ in ()).throw(Refused('no such turtle')), stopped=lambda: False)
    finally:
        stop.set()
        thread.join()


def test_refusals_nobody_waits_for_go_to_on_error_and_bugs_propagate():
    heard = []
    queue = RequestQueue(expected=(Refused,), on_error=heard.append)
    queue.submit(lambda: (_ for _ in ()).throw(Refused('bad cmd_vel')))
    after = queue.submit(lambda: 'still runs')
    queue.run_pending()
    assert [str(error) for error in heard] == ['bad cmd_vel'] and after.result == 'still runs'
    queue.submit(lambda: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        queue.run_pending()


def test_a_stopping_simulator_fails_its_callers_instead_of_leaving_them_waiting():
    queue = RequestQueue()
    with pytest.raises(Stopped):
        queue.call(lambda: 1, stopped=lambda: True, poll=0.001)
    pending = queue.submit(lambda: 1, waited=True)
    queue.fail_pending(Stopped('shutting down'))
    assert pending.done.is_set() and isinstance(pending.error, Stopped)
