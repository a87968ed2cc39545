import io
import os
import signal
import subprocess
import sys

import pytest

from course_common.keyboard import KeyReader, NoTerminalError
from course_testing.processes import PtyProgram


def test_without_a_terminal_the_reader_refuses_with_one_sentence():
    with pytest.raises(NoTerminalError) as err:
        with KeyReader('my_teleop', stream=io.StringIO()):
            pass
    message = str(err.value)
    assert message.startswith('my_teleop reads the keyboard')
    assert 'not a terminal' in message and '\n' not in message


ECHO_KEYS = '''
from course_common.keyboard import KeyReader, write_line
with KeyReader('echo') as keys:
    write_line('ready')
    while True:
        key = keys.read(5.0)
        if key in (None, 'q'):
            break
        write_line('key %r' % key)
write_line('bye')
'''


def test_keys_arrive_one_byte_at_a_time_without_enter():
    program = PtyProgram([sys.executable, '-c', ECHO_KEYS])
    try:
        program.wait_for_output('ready', 10)
        program.type('i\x1b[A')
        out = program.wait_for_output("key 'A'", 5)
        assert "key 'i'" in out and "key '\\x1b'" in out and "key '['" in out
        program.type('q')
        program.wait_for_output('bye', 5)
        assert program.process.wait(5) == 0
    finally:
        program.stop()


CLOSE_TERMINAL_WHILE_RAW = '''
import os, sys
from course_common.keyboard import KeyReader
with KeyReader('closer') as keys:
    os.close(sys.stdin.fileno())  # as if the terminal disappeared under the program
print('left cleanly')
'''


def test_leaving_raw_mode_after_the_terminal_is_gone_is_not_an_error():
    program = PtyProgram([sys.executable, '-c', CLOSE_TERMINAL_WHILE_RAW])
    try:
        assert program.process.wait(10) == 0
        assert 'left cleanly' in program.read_available()
    finally:
        program.stop()


TELEOP = '''
import os, signal, sys
from course_common.keyboard import teleop_keys, write_line
# As rospy's handler would shut down. A raw os.write: a signal that interrupts write_line('ready')
# runs this handler inside that write, where a second buffered write to stdout is refused.
signal.signal(signal.SIGINT, lambda *_: os.write(sys.stdout.fileno(), b'interrupted\\r\\n'))
with teleop_keys('teleop') as keys:
    write_line('ready')
    while keys.read(5.0) != 'q':
        pass
'''


def test_teleop_keys_without_a_terminal_prints_one_sentence_and_exits_1():
    result = subprocess.run([sys.executable, '-c', TELEOP], stdin=subprocess.DEVNULL,
                            capture_output=True, text=True, timeout=30)
    assert result.returncode == 1
    assert result.stdout == ''
    assert result.stderr.startswith('teleop reads the keyboard, but its standard input is not a')
    assert len(result.stderr.splitlines()) == 1


def test_teleop_keys_turns_a_hang_up_into_sigint_and_the_lost_terminal_into_a_quit():
    program = PtyProgram([sys.executable, '-c', TELEOP])
    try:
        program.wait_for_output('ready', 10)
        program.process.send_signal(signal.SIGHUP)
        program.wait_for_output('interrupted', 15)   # a bound, not a pause: a busy machine runs the handler late
        assert program.process.poll() is None  # SIGINT's handler ran instead of SIGHUP killing it
        os.close(program._fd)  # the terminal window goes away: the next read fails
        program._fd = os.open(os.devnull, os.O_RDONLY)  # (so that stop() has something to close)
        assert program.process.wait(10) == 0  # the key loop ended without a traceback
    finally:
        program.stop()
