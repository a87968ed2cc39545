"""course_checks.launch.Launch: the output of a command is read to its end whatever happens to its log."""
import errno
import subprocess
import threading

import pytest

from course_checks.launch import Launch

LINES = 100000   # far more than a pipe holds (64 KiB): the command ends only if we keep reading


def test_a_full_disk_ends_the_log_but_not_the_reading():
    # /dev/full refuses every write (ENOSPC), as a log folder on a disk a submission filled.
    launch = Launch(['seq', str(LINES)], log_path='/dev/full')
    assert launch.process.wait(timeout=30) == 0
    launch.stop()
    assert launch.lines[-1] == str(LINES)


def test_the_log_keeps_the_output(tmp_path):
    log = tmp_path / 'seq.log'
    launch = Launch(['seq', '3'], log_path=str(log))
    assert launch.process.wait(timeout=30) == 0
    launch.stop()
    assert log.read_text() == '1\n2\n3\n'
    assert launch.lines == ['1', '2', '3']


def test_no_thread_left_to_read_is_an_error_and_leaves_no_program(monkeypatch, tmp_path):
    # A sandbox whose processes a fork bomb took: the program may start, its reader not. A program
    # whose output nobody reads would block at its next line: it is stopped, and the caller told
    # as for a program that could not start at all (OSError, EAGAIN).
    started = []
    real_popen = subprocess.Popen

    def popen(*args, **kwargs):
        started.append(real_popen(*args, **kwargs))
        return started[-1]

    def no_thread(_thread):
        raise RuntimeError("can't start new thread")
    monkeypatch.setattr(subprocess, 'Popen', popen)
    monkeypatch.setattr(threading.Thread, 'start', no_thread)
    with pytest.raises(OSError) as raised:
        Launch(['sleep', '60'], log_path=str(tmp_path / 'sleep.log'))
    assert raised.value.errno == errno.EAGAIN
    assert str(raised.value) == '[Errno 11] no thread left to read the output of sleep'
    assert started[0].poll() is not None   # stopped, and waited for
