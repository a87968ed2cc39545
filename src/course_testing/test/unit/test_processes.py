import os
import signal
import socket
import subprocess
import sys
import threading

from course_common.process_table import command_line, user_processes
from course_common import processes
from course_common.processes import free_port, port_open, stop_process_group, together
from course_testing.processes import ReadPtyProgram, ignored_signals, run
from course_common.waiting import wait_until

# The programs below wait in short sleeps, as rospy.spin does. Python runs a signal handler between
# its own steps: a signal that came after the print but before sleep's system call would be handled
# only when a long sleep ends (a minute late, seen on a busy machine).
WAIT_A_MINUTE = 'for _ in range(1200): time.sleep(0.05)'

TRAPS_SIGINT = '''
import signal, sys, time
signal.signal(signal.SIGINT, lambda *_: sys.exit(7))
print('ready', flush=True)
''' + WAIT_A_MINUTE

IGNORES_SIGINT = '''
import signal, time
signal.signal(signal.SIGINT, signal.SIG_IGN)
print('ready', flush=True)
time.sleep(60)
'''


def start(code):
    process = subprocess.Popen([sys.executable, '-c', code], stdout=subprocess.PIPE,
                               start_new_session=True, universal_newlines=True)
    assert process.stdout.readline().strip() == 'ready'
    return process


def test_a_program_gets_sigint_first_and_can_shut_down_cleanly():
    assert stop_process_group(start(TRAPS_SIGINT)) == 7


def test_a_program_that_ignores_sigint_is_killed_after_the_timeout():
    assert stop_process_group(start(IGNORES_SIGINT), timeout=0.5) == -9


# On SIGINT it writes a file (as a ROS node leaves the graph), then takes a minute to end.
SLOW_TO_END = '''
import signal, sys, time
def stop(*_):
    open(sys.argv[1], 'w').close()
    time.sleep(60)
    sys.exit(7)
signal.signal(signal.SIGINT, stop)
print('ready', flush=True)
''' + WAIT_A_MINUTE


def test_a_program_is_killed_as_soon_as_it_has_stopped_by_the_callers_measure(tmp_path):
    left = tmp_path / 'left'
    process = subprocess.Popen([sys.executable, '-c', SLOW_TO_END, str(left)], stdout=subprocess.PIPE,
                               start_new_session=True, universal_newlines=True)
    assert process.stdout.readline().strip() == 'ready'
    assert stop_process_group(process, timeout=50, stopped=left.exists) == -9   # not 7, after a minute
    assert left.exists()


def test_a_program_that_never_stops_by_the_callers_measure_is_killed_after_the_timeout():
    assert stop_process_group(start(IGNORES_SIGINT), timeout=0.5, stopped=lambda: False) == -9


def test_stopping_a_finished_program_returns_its_exit_code():
    process = subprocess.Popen([sys.executable, '-c', 'raise SystemExit(3)'], start_new_session=True)
    process.wait()
    assert stop_process_group(process) == 3


def test_a_free_port_can_be_listened_on():
    port = free_port()
    assert 1024 < port < 65536
    with socket.socket() as server:
        server.bind(('127.0.0.1', port))
        server.listen()


def test_a_free_port_is_never_one_the_kernel_hands_out_by_itself_nor_the_users_master():
    low, high = processes.kernel_ports()
    ports = [free_port() for _ in range(300)]
    assert [port for port in ports if low <= port <= high or port == 11311 or port < 10000] == []
    assert len(set(ports)) > 250   # at random: two callers rarely meet


def test_a_port_something_listens_on_is_not_chosen(monkeypatch):
    # Two neighbouring ports, the first held by a listener, are free_port's first two tries.
    taken = None
    while taken is None:
        port = free_port()
        if port + 1 < 65536 and processes._bindable(port + 1):
            taken = port
    with socket.socket() as listener:
        listener.bind(('127.0.0.1', taken))
        listener.listen()
        tried = iter([taken, taken + 1])
        monkeypatch.setattr(processes._RANDOM, 'randrange', lambda low, high: next(tried))
        assert free_port() == taken + 1


def test_where_the_kernel_keeps_every_port_one_of_its_own_is_used(monkeypatch):
    low, high = processes.kernel_ports()   # this machine's
    monkeypatch.setattr(processes, 'kernel_ports', lambda: (1024, 65535))
    port = free_port()
    assert low <= port <= high
    assert processes._bindable(port)


# A program started as a background job is (SIGINT and SIGQUIT ignored), which calls restore_ctrl_c and
# then starts a roslaunch stand-in that relies on the default SIGINT (KeyboardInterrupt).
RESTORES_THEN_STARTS = '''
import subprocess, sys
from course_common.processes import restore_ctrl_c
restore_ctrl_c()
child = subprocess.Popen([sys.executable, '-c', "import time; print('ready', flush=True); time.sleep(60)"],
                         stdout=subprocess.PIPE, universal_newlines=True)
child.stdout.readline()
print(open('/proc/%d/status' % child.pid).read(), flush=True)
child.kill()
'''


def test_restore_ctrl_c_gives_the_programs_started_after_it_the_default_sigint():
    def as_a_background_job():
        for number in (signal.SIGINT, signal.SIGQUIT):
            signal.signal(number, signal.SIG_IGN)

    result = subprocess.run([sys.executable, '-c', RESTORES_THEN_STARTS], stdout=subprocess.PIPE,
                            universal_newlines=True, timeout=30, preexec_fn=as_a_background_job)
    assert result.returncode == 0
    assert not {signal.SIGINT, signal.SIGQUIT} & ignored_signals(result.stdout)
    # Without it, the program inherits the background job's ignored SIGINT.
    unrestored = RESTORES_THEN_STARTS.replace('restore_ctrl_c()\n', '')
    result = subprocess.run([sys.executable, '-c', unrestored], stdout=subprocess.PIPE,
                            universal_newlines=True, timeout=30, preexec_fn=as_a_background_job)
    assert signal.SIGINT in ignored_signals(result.stdout)


def test_a_port_is_open_while_something_listens_on_it():
    with socket.socket() as server:
        server.bind(('127.0.0.1', 0))
        server.listen()
        port = server.getsockname()[1]
        assert port_open(port)
    assert not port_open(port)


def test_run_gives_the_exit_code_and_both_outputs_in_order():
    code, output = run(sys.executable, '-c', 'import sys; print("out", flush=True); sys.exit("err")')
    assert (code, output) == (1, 'out\nerr\n')


def test_a_read_program_that_prints_more_than_a_terminal_holds_does_not_block():
    # 1 MB into a pseudo-terminal nobody reads would block the program at about 4 kB.
    program = ReadPtyProgram([sys.executable, '-c', 'print("x" * 1000000); print("done")'])
    assert program.process.wait(30) == 0
    assert program.stop() == 0
    assert program.output.rstrip().endswith('done')


# A program that starts a child in a session of its own and stops it in a finally block.
STOPS_ITS_CHILD_IN_FINALLY = '''
import signal, subprocess, sys, time
from course_common.processes import exit_on_terminate
if sys.argv[1] == 'handled':
    exit_on_terminate()
else:   # the default, even where the test runs with SIGHUP ignored (nohup) and a child inherits that
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGHUP, signal.SIG_DFL)
child = subprocess.Popen(['sleep', '600'], start_new_session=True)
try:
    print(child.pid, flush=True)
    for _ in range(12000):
        time.sleep(0.05)
finally:
    child.kill()
'''


def test_on_sigterm_and_sighup_a_program_runs_its_finally_blocks():
    for number in (signal.SIGTERM, signal.SIGHUP):
        for handled in ('handled', 'default'):
            program = subprocess.Popen([sys.executable, '-c', STOPS_ITS_CHILD_IN_FINALLY, handled],
                                       stdout=subprocess.PIPE, universal_newlines=True)
            child = int(program.stdout.readline())
            program.send_signal(number)
            code = program.wait(30)
            try:
                if handled == 'handled':
                    assert code == 128 + number
                    wait_until(lambda: child not in user_processes(os.getuid()), 10, 'the child to be stopped')
                else:   # Python's default: the program ends at once, its child goes on
                    assert code == -number
                    # Waited for: the kernel lets the program's Popen return while the child's new
                    # command line is not yet in place (empty for a moment, on a busy machine).
                    wait_until(lambda: command_line(child) == '%d sleep 600' % child, 10, 'the child to go on')
            finally:
                if handled == 'default':
                    os.kill(child, signal.SIGKILL)


def test_together_runs_the_calls_at_once_and_each_alone_when_no_thread_starts(monkeypatch):
    first, second = threading.Event(), threading.Event()
    seen = []

    def one():   # each waits for the other: only calls made at once both see it
        first.set()
        seen.append(second.wait(5))

    def other():
        second.set()
        seen.append(first.wait(5))
    together(one, other)
    assert seen == [True, True]

    def no_thread(self):
        raise RuntimeError("can't start new thread")
    monkeypatch.setattr(threading.Thread, 'start', no_thread)
    order = []
    together(lambda: order.append('first'), lambda: order.append('second'))
    assert sorted(order) == ['first', 'second']
