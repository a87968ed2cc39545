"""Starting and stopping programs, by the grader's trusted side, the checks, the tests and the tour:
a free port for a private master, Ctrl-C as in a terminal, a process group stopped."""
import os
import random
import signal
import socket
import subprocess
import threading

from course_common.waiting import poll_until


# The range Linux gives ports from by itself (to a connection's own end, to a bind to port 0) when
# /proc does not say, and the port of the user's own roscore.
KERNEL_PORTS = (32768, 60999)
USERS_MASTER_PORT = 11311
# The lowest port free_port chooses: below it, servers a machine may run on fixed ports (databases,
# X displays' 6000 + n).
PRIVATE_PORTS_FROM = 10000


def kernel_ports(path='/proc/sys/net/ipv4/ip_local_port_range'):
    """The range of ports (lowest, highest) Linux hands out by itself."""
    try:
        with open(path) as text:
            low, high = (int(field) for field in text.read().split())
        return low, high
    except (OSError, ValueError):
        return KERNEL_PORTS


def free_port(tries=100):
    """A TCP port that is free on loopback now, for a private master: never the user's 11311, and
    outside the range Linux hands out by itself. A port from a bind to port 0 is in that range, and
    the kernel may give it to any other program's connection or listener (a node's, another test's)
    before our master binds it; the master then cannot start (the likely cause of a test's master
    that did not answer in CI, 2026-12-05). Chosen at random, so that two callers rarely pick the
    same one; where no port tried will do (the kernel keeps them all), one from the kernel."""
    low, high = kernel_ports()
    for _ in range(tries):
        port = _RANDOM.randrange(PRIVATE_PORTS_FROM, 65536)
        if not low <= port <= high and port != USERS_MASTER_PORT and _bindable(port):
            return port
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


_RANDOM = random.SystemRandom()


def _bindable(port):
    with socket.socket() as probe:
        try:
            probe.bind(('127.0.0.1', port))
        except OSError:
            return False
    return True


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
