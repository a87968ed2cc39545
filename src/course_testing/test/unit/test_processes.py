import socket
import subprocess
import sys

from course_testing.processes import free_port, stop_process_group

TRAPS_SIGINT = '''
import signal, sys, time
signal.signal(signal.SIGINT, lambda *_: sys.exit(7))
print('ready', flush=True)
time.sleep(60)
'''

IGNORES_SIGINT = '''
import signal, time
signal.signal(signal.SIGINT, signal.SIG_IGN)
print('ready', flush=True)
time.sleep(60)
'''


def start(code):
    process = subprocess.Popen([sys.executable, '-c', code], stdout=subprocess.PIPE,
                               start_new_session=True, universal_newlines=True)
    assert process.stdout.readline().strip() == 'ready'
    return process


def test_a_program_gets_sigint_first_and_can_shut_down_cleanly():
    assert stop_process_group(start(TRAPS_SIGINT)) == 7


def test_a_program_that_ignores_sigint_is_killed_after_the_timeout():
    assert stop_process_group(start(IGNORES_SIGINT), timeout=0.5) == -9


def test_stopping_a_finished_program_returns_its_exit_code():
    process = subprocess.Popen([sys.executable, '-c', 'raise SystemExit(3)'], start_new_session=True)
    process.wait()
    assert stop_process_group(process) == 3


def test_a_free_port_can_be_listened_on():
    port = free_port()
    assert 1024 < port < 65536
    with socket.socket() as server:
        server.bind(('127.0.0.1', port))
        server.listen()
