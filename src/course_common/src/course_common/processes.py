"""Starting and stopping what a test, a benchmark or the tour runs beside the user's programs."""
import os
import signal
import socket
import subprocess


def free_port():
    """A TCP port that is free on loopback now: for a private master, so that we never meet (or
    take) one the user runs on 11311."""
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def stop_process_group(process, timeout=15.0):
    """SIGINT a process started with start_new_session=True and everything it started (as Ctrl-C
    in a terminal would, so ROS nodes shut down cleanly and save what they save at shutdown);
    SIGKILL the group if it is still there after timeout seconds. Returns the exit code."""
    if process.poll() is None:
        try:
            os.killpg(process.pid, signal.SIGINT)
            process.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        except ProcessLookupError:
            process.wait()
    return process.returncode
