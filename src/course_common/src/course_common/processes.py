"""Starting and stopping programs, by the grader's trusted side, the checks, the tests and the tour:
a free port for a private master, Ctrl-C as in a terminal, a process group stopped."""
import os
import signal
import socket
import subprocess
import threading

from course_common.waiting import poll_until


def free_port():
    """A TCP port that is free on loopback now: for a private master, so that we never meet (or
    take) one the user runs on 11311."""
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def port_open(port):
    """Something listens on this TCP port of loopback (a server a test started is up)."""
    with socket.socket() as probe:
        return probe.connect_ex(('127.0.0.1', port)) == 0


def restore_ctrl_c():
    """Let SIGINT (Ctrl-C) and SIGQUIT reach this process and every program it starts, as in a
    terminal. A shell starts a background job (`./grade.sh ... &`, a script's `cmd &`, some CI
    runners) with both ignored, and programs inherit that: roscore and roslaunch then ignore the
    SIGINT of stop_process_group and are killed only at its timeout (the network tests took twice
    as long, and a grader would say that a correct node did not stop on Ctrl-C)."""
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGQUIT, signal.SIG_DFL)


def exit_on_terminate():
    """SIGTERM (`kill`, a CI job cancelled, a test's timeout) and SIGHUP (the terminal closed)
    raise SystemExit in the main thread, as Ctrl-C raises KeyboardInterrupt: the program's finally
    and with blocks then stop what it started (by default both end Python at once, and roscore and
    roslaunch, in sessions of their own, go on without it). Exit status 128 + the signal's number."""
    def leave(number, _frame):
        raise SystemExit(128 + number)
    signal.signal(signal.SIGTERM, leave)
    signal.signal(signal.SIGHUP, leave)


def stop_process_group(process, timeout=15.0, stopped=None):
    """SIGINT a process started with start_new_session=True and everything it started (as Ctrl-C
    in a terminal would, so ROS nodes shut down cleanly and save what they save at shutdown);
    SIGKILL the group if it is still there after timeout seconds, or as soon as stopped() holds
    (a ROS node that has left the graph: what is left is its exit). Returns the exit code."""
    if process.poll() is None:
        try:
            os.killpg(process.pid, signal.SIGINT)
            if stopped is None:
                process.wait(timeout)
            elif not poll_until(lambda: process.poll() is not None or stopped(), timeout):
                raise subprocess.TimeoutExpired(process.args, timeout)
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        except ProcessLookupError:
            process.wait()
    return process.returncode


def together(*calls):
    """Call each function at once, each on a thread, and return when all have returned; one after
    the other when no thread can start (a sandbox whose processes a fork bomb took)."""
    threads = []
    for call in calls[1:]:
        thread = threading.Thread(target=call)
        try:
            thread.start()
        except RuntimeError:   # can't start new thread
            call()
            continue
        threads.append(thread)
    calls[0]()
    for thread in threads:
        thread.join()
