"""A command (roslaunch, rosrun, a student's script) run as a student runs it, in a session of its
own, its output kept line by line (bounded: a node printing without end stays within memory), and
stopped as Ctrl-C in a terminal stops it."""
import collections
import errno
import os
import re
import signal
import subprocess
import threading
import time

from course_common.processes import stop_process_group

MAX_LINES = 5000             # lines of output kept in memory
MAX_LOG_BYTES = 5 * 2 ** 20  # of output written to the log file
COLOUR = re.compile(r'\x1b\[[0-9;]*m')   # rosconsole and roslaunch colour their lines


class Launch:
    """`argv` started in a session of its own (stdin closed, stdout and stderr together), with
    `env` (default: ours) and, when given, as another `user` (the grader's sandbox runs the
    student's side so); with `log_path`, the output is logged there too (the first MAX_LOG_BYTES)."""

    def __init__(self, argv, log_path=None, env=None, user=None, cwd=None):
        # Unbuffered, so that what the nodes print reaches us line by line, as in a terminal.
        env = dict(os.environ if env is None else env, PYTHONUNBUFFERED='1')
        as_user = {'user': user, 'group': user, 'extra_groups': []} if user else {}
        self._lines = collections.deque(maxlen=MAX_LINES)   # (time.monotonic() it was read, line)
        self._lock = threading.Lock()
        self._log = open(log_path, 'w', errors='replace') if log_path else None
        self.process = subprocess.Popen(list(argv), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, env=env, cwd=cwd, text=True,
                                        errors='replace', start_new_session=True, **as_user)
        self._reader = threading.Thread(target=self._read, daemon=True)
        try:
            self._reader.start()
        except RuntimeError:   # can't start new thread: a program nobody reads would block, so none
            stop_process_group(self.process, 0)
            self.process.stdout.close()
            if self._log:
                self._log.close()
            raise OSError(errno.EAGAIN, 'no thread left to read the output of %s' % os.path.basename(argv[0]))

    def _read(self):
        logged = 0
        for line in self.process.stdout:
            with self._lock:
                self._lines.append((time.monotonic(), line.rstrip('\n')))
            if self._log and logged < MAX_LOG_BYTES:
                try:
                    self._log.write(line)
                    logged += len(line)
                    if logged >= MAX_LOG_BYTES:
                        self._log.write('\n[output cut here, %d bytes kept]\n' % MAX_LOG_BYTES)
                    self._log.flush()
                except OSError:
                    # A full disk ends the log, never the reading: a pipe nobody drains would stop
                    # the program at its next line (roscore's master, holding its lock, stops them all).
                    logged = MAX_LOG_BYTES
        if self._log:
            try:
                self._log.close()
            except OSError:
                pass

    @property
    def lines(self):
        return [line for _, line in self.timed_lines()]

    def timed_lines(self):
        """(time.monotonic() the line was read, line) of each line kept: when a node printed it, to
        compare with when what it printed was published."""
        with self._lock:
            return list(self._lines)

    @property
    def output(self):
        return '\n'.join(self.lines)

    def ended(self):
        return self.process.poll() is not None

    def error_lines(self, count=2):
        """The first lines that look like errors (roslaunch's red ones, exceptions), joined: a hint
        of why nothing came of the command."""
        lines = [COLOUR.sub('', line).strip() for line in self.lines]
        errors = [line for line in lines if 'ERROR' in line or 'rror' in line or 'Exception' in line or 'not found' in line]
        return ' | '.join(errors[:count]) or 'no error printed'

    def stop(self, timeout=30, stopped=None):
        """Ctrl-C, as in the terminal (roslaunch stops its nodes), killed after `timeout` seconds,
        or as soon as stopped() holds (a node that left the ROS graph: all that is left is its exit).
        True when it stopped in time, False when it had to be killed, None when it had already ended."""
        if self.process.poll() is not None:
            self._reader.join(5)
            return None
        code = stop_process_group(self.process, timeout, stopped)
        self._reader.join(5)
        return code != -signal.SIGKILL or bool(stopped and stopped())
