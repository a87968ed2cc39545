"""Stopping what a test, the tour or a launch helper started."""
import os
import signal
import subprocess


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
