"""Starting, driving and stopping what a test, a benchmark or the tour runs beside the user's programs."""
import os
import pty
import select
import signal
import socket
import subprocess
import threading

from course_testing.waiting import poll_until, wait_until


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


def run(*argv, timeout=60):
    """Run a command (rostopic, rosrun ...) to its end; its exit code and everything it printed
    (standard output and error as they came)."""
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                            timeout=timeout)
    return result.returncode, result.stdout


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


def ignored_signals(status_text):
    """The signal numbers a /proc/PID/status text (its SigIgn line) says the process ignores."""
    mask = next(int(line.split()[1], 16) for line in status_text.splitlines() if line.startswith('SigIgn:'))
    return {number for number in range(1, 65) if mask & (1 << (number - 1))}


def build_environment(devel):
    """The environment a shell has after sourcing the setup.bash of another build of this
    workspace (its devel folder), with this process's master: to run that build's nodes beside
    this one's in a benchmark."""
    output = subprocess.run(['bash', '-c', 'source "$0/setup.bash" && env -0', devel], check=True,
                            stdout=subprocess.PIPE).stdout
    environment = dict(line.split('=', 1) for line in output.decode().split('\0') if '=' in line)
    environment['PATH'] = '/usr/bin:' + environment.get('PATH', '')
    environment['ROS_MASTER_URI'] = os.environ['ROS_MASTER_URI']
    return environment


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


class PtyProgram:
    """A program whose standard input and output are a pseudo-terminal, as if a user typed."""

    def __init__(self, argv, env=None):
        master, slave = pty.openpty()
        self.process = subprocess.Popen(argv, stdin=slave, stdout=slave, stderr=slave, env=env,
                                        close_fds=True, start_new_session=True)
        os.close(slave)
        self._fd = master
        self.output = ''

    def type(self, keys):
        """Send key presses (a str; arrow keys as their escape sequences)."""
        os.write(self._fd, keys.encode('latin-1'))

    def read_available(self, timeout=0.05):
        """Append whatever the program printed within timeout seconds to self.output."""
        while True:
            ready, _, _ = select.select([self._fd], [], [], timeout)
            if not ready:
                return self.output
            try:
                chunk = os.read(self._fd, 4096)
            except OSError:  # the program exited and closed the pty
                return self.output
            if not chunk:
                return self.output
            self.output += chunk.decode('utf-8', 'replace')
            timeout = 0

    def wait_for_output(self, text, timeout):
        """Wait until `text` appears in what the program printed; returns all output."""
        return wait_until(lambda: text in self.read_available() and self.output, timeout,
                          what='%r in the output of %s' % (text, self.process.args[0]))

    def stop(self, timeout=10):
        """SIGINT the program (as Ctrl-C in a shell would), then kill it if it hangs; returns exit code."""
        stop_process_group(self.process, timeout)
        self.read_available(0)
        os.close(self._fd)
        return self.process.returncode


class ReadPtyProgram(PtyProgram):
    """A PtyProgram whose output a thread keeps reading: a program nobody reads blocks once the
    terminal's buffer is full (a ROS node that cannot write its log lines stalls)."""

    def __init__(self, argv, env=None):
        super().__init__(argv, env)
        self._reading = True
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        while self._reading:
            self.read_available(0.05)

    def stop(self, timeout=10):
        """Ctrl-C, read until everything it started has stopped; returns the exit code."""
        stop_process_group(self.process, timeout)
        self._reading = False
        self._reader.join()
        return super().stop(timeout)
