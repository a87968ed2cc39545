"""Single key presses from the terminal, for the keyboard teleops.

The teleops read one byte at a time from a terminal in raw mode, as the ROS originals do, so that a
key acts the moment it is pressed. Without a terminal (roslaunch without a console, CI, `docker run`
without -t) there is nothing to read from: KeyReader raises NoTerminalError with one sentence the
teleop prints before it exits. teleop_keys() wraps KeyReader with the rest of the terminal side
every teleop shares.
"""
import contextlib
import os
import select
import signal
import sys
import termios
import tty


class NoTerminalError(RuntimeError):
    """Standard input is not a terminal, so no key presses can be read."""


class KeyReader:
    """Context manager: puts a terminal in raw mode and reads single key presses from it.

    Arrow keys arrive as escape sequences (ESC [ A ...), one byte per read, exactly like the
    originals read them; the teleops decide what each byte means.
    """

    def __init__(self, program, stream=None):
        self.program = program
        self.stream = stream if stream is not None else sys.stdin
        self._saved_mode = None

    def __enter__(self):
        if not self.stream.isatty():
            raise NoTerminalError(
                '%s reads the keyboard, but its standard input is not a terminal: '
                'run it in a terminal (roslaunch/rosrun in a shell, or docker run -it).'
                % self.program)
        fd = self.stream.fileno()
        self._saved_mode = termios.tcgetattr(fd)
        tty.setraw(fd)
        return self

    def __exit__(self, *exc):
        try:
            termios.tcsetattr(self.stream.fileno(), termios.TCSADRAIN, self._saved_mode)
        except (termios.error, OSError):
            pass  # the terminal was closed under us: there is no mode left to restore
        return False

    def read(self, timeout=None):
        """One key byte as a 1-character str, or None if nothing came within timeout seconds.

        Ctrl-C arrives as '\\x03' (raw mode turns off SIGINT): callers treat it as quit.
        End of input (the terminal closed) raises EOFError.
        """
        fd = self.stream.fileno()
        ready, _, _ = select.select([fd], [], [], timeout)
        if not ready:
            return None
        data = os.read(fd, 1)
        if not data:
            raise EOFError('the terminal was closed')
        return data.decode('latin-1')


@contextlib.contextmanager
def teleop_keys(program):
    """KeyReader for a teleop's key loop, with the terminal side every keyboard teleop shares.

    - Without a terminal: prints NoTerminalError's sentence on stderr and exits with status 1.
    - Closing the terminal window sends SIGHUP, which would end the program on the spot (no
      clean shutdown, no stop command): it is turned into SIGINT, so the program ends as after
      Ctrl-C in a shell (for a ROS node, rospy's SIGINT handler shuts the node down cleanly).
    - The terminal going away during a read or a write (EOFError, or EIO as OSError) ends the
      key loop, as a quit key does.
    """
    signal.signal(signal.SIGHUP, lambda *_: os.kill(os.getpid(), signal.SIGINT))
    try:
        with KeyReader(program) as keys:
            yield keys
    except NoTerminalError as error:
        sys.stderr.write('%s\n' % error)
        sys.exit(1)
    except (EOFError, OSError):
        pass  # the terminal went away: nothing more to read or show


def write_line(text, stream=None):
    """Print a line while the terminal is raw (raw mode needs an explicit carriage return)."""
    out = stream if stream is not None else sys.stdout
    out.write(text.replace('\n', '\r\n') + '\r\n')
    out.flush()
