"""Starting, driving and stopping what a test, a benchmark or the tour runs beside the user's programs."""
import contextlib
import os
import pty
import select
import subprocess
import threading

from course_common.processes import stop_process_group
from course_common.waiting import wait_until


def run(*argv, timeout=60):
    """Run a command (rostopic, rosrun ...) to its end; its exit code and everything it printed
    (standard output and error as they came)."""
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                            timeout=timeout)
    return result.returncode, result.stdout


def ignored_signals(status_text):
    """The signal numbers a /proc/PID/status text (its SigIgn line) says the process ignores."""
    mask = next(int(line.split()[1], 16) for line in status_text.splitlines() if line.startswith('SigIgn:'))
    return {number for number in range(1, 65) if mask & (1 << (number - 1))}


@contextlib.contextmanager
def busy_core(wanted=True):
    """For the block, a process that keeps one core busy (none when not wanted): what a test or a
    bench must hold beside, since the course's machines have two cores shared with other work."""
    process = (subprocess.Popen(['/usr/bin/python3', '-c', 'while True: pass'], start_new_session=True,
                                stderr=subprocess.DEVNULL) if wanted else None)   # no KeyboardInterrupt's traceback
    try:
        yield
    finally:
        if process:
            stop_process_group(process)


@contextlib.contextmanager
def other_master():
    """For the block, a ROS master of another program's on a port of its own (yields the port):
    what a session that chose that port must not take for its own."""
    import rosgraph
    from course_common.processes import free_port
    port = free_port()
    process = subprocess.Popen(['rosmaster', '--core', '-p', str(port)], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        wait_until(lambda: rosgraph.Master('/test', master_uri='http://127.0.0.1:%d' % port).is_online(), 30,
                   'the other program\'s master')
        yield port
    finally:
        stop_process_group(process)


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


class LoggedLaunch:
    """A roslaunch (or any command) in a session of its own, its output in a file read back by
    `output()`; `stop()` stops its process group with SIGINT, as Ctrl-C would."""

    def __init__(self, argv, log_path, env):
        self.log_path = log_path
        self._log = open(log_path, 'w')
        # Unbuffered: roslaunch's own lines (and its Python nodes') reach the file as printed.
        self.process = subprocess.Popen(argv, stdout=self._log, stderr=subprocess.STDOUT,
                                        stdin=subprocess.DEVNULL, env=dict(env, PYTHONUNBUFFERED='1'),
                                        start_new_session=True)

    def exited(self):
        """Whether it has ended (a REQUIRED node that died ends a roslaunch)."""
        return self.process.poll() is not None

    def output(self):
        with open(self.log_path, errors='replace') as log:
            return log.read()

    def stop(self, timeout=20.0):
        try:
            stop_process_group(self.process, timeout)
        finally:
            self._log.close()
