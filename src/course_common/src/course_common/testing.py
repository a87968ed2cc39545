"""Test helpers: wait for a condition instead of sleeping, and drive a program through a pty."""
import os
import pty
import select
import subprocess
import time

from course_common.processes import stop_process_group


def wait_until(condition, timeout, what='the condition', poll=0.01):
    """Poll condition() until it returns a true value and return that value.

    Raises AssertionError naming `what` when timeout seconds pass first, so a test fails with a
    sentence rather than hanging or passing by luck.
    """
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError('timed out after %.1f s waiting for %s' % (timeout, what))
        time.sleep(poll)


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
