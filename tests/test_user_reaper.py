"""course_common.process_table.UserReaper, the grader's last word on a student's processes (docs/grading.md,
"take the machine or the time"): started before the student has any, it kills every one of them at once,
a fork bomb and daemons in sessions of their own included; they can neither signal nor trace it; and it is still there
for the next run. Needs root, to run as a second user (./test.sh leaves this file out for an ordinary user)."""
import os
import subprocess
import sys

import pytest

from course_common.process_table import UserReaper, stop_user, user_processes
from course_common.waiting import wait_until

# Forks without end, each process the same, at most NPROC of the user's processes at once (the
# container's process limit, smaller, so that the test machine keeps its own).
NPROC = 150
FORK_BOMB = '''
import os, resource, time
resource.setrlimit(resource.RLIMIT_NPROC, (%d, %d))
while True:
    try:
        os.fork()
    except OSError:
        time.sleep(0.01)
''' % (NPROC, NPROC)
# A daemon: a session of its own, its parent gone, so that init is its parent and no group reaches it.
DAEMON = 'import os, time\nif os.fork() == 0:\n    os.setsid()\n    time.sleep(600)\n'


def free_uid():
    """A user id no process has (a process may run as a user id without an account)."""
    return next(uid for uid in range(47000, 48000) if not user_processes(uid))


@pytest.fixture
def student():
    assert os.geteuid() == 0, 'the reaper drops root: run as root (./test.sh leaves this file out without it)'
    uid = free_uid()
    reaper = UserReaper(uid)
    wait_until(lambda: reaper.process.pid in user_processes(uid), 10, 'the reaper to take the user id')
    yield uid, reaper
    reaper.close()
    stop_user(uid)   # what a failed test left


def as_user(uid, program):
    return subprocess.run([sys.executable, '-c', program], user=uid, group=uid, extra_groups=[],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=30)


def start_daemon(uid):
    subprocess.run([sys.executable, '-c', DAEMON], user=uid, group=uid, extra_groups=[], stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL, timeout=30, check=True)


def start_bomb_and_daemon(uid):
    bomb = subprocess.Popen([sys.executable, '-c', FORK_BOMB], user=uid, group=uid, extra_groups=[],
                            start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    start_daemon(uid)
    wait_until(lambda: len(user_processes(uid)) >= NPROC * 2 // 3, 30, 'the fork bomb to fill its process limit')
    return bomb


def students_processes(uid, reaper):
    return [pid for pid in user_processes(uid) if pid != reaper.process.pid]


def assert_bomb_and_daemon_killed_at_once(uid, reaper):
    bomb = start_bomb_and_daemon(uid)
    assert reaper.kill_all()
    assert students_processes(uid, reaper) == []
    bomb.wait(10)


def test_a_fork_bomb_and_a_daemon_are_killed_at_once(student):
    assert_bomb_and_daemon_killed_at_once(*student)


# What a student's process may try against the reaper: kill it, stop it (it would then answer no
# more), trace it (and make it do nothing), read its memory, make it the kernel's first choice when
# memory runs out (then a submission that fills it would have it killed). Each prints one word.
AGAINST_THE_REAPER = '''
import ctypes, os, signal
pid = %d
for name in ('SIGKILL', 'SIGSTOP', 'SIGTERM'):
    try:
        os.kill(pid, getattr(signal, name))
        print(name, 'sent')
    except PermissionError:
        print(name, 'refused')
libc = ctypes.CDLL(None, use_errno=True)
PTRACE_ATTACH = 16
print('ptrace', 'refused' if libc.ptrace(PTRACE_ATTACH, pid, None, None) == -1 else 'attached')
try:
    open('/proc/%%d/mem' %% pid, 'rb').close()
    print('memory opened')
except PermissionError:
    print('memory refused')
try:
    with open('/proc/%%d/oom_score_adj' %% pid, 'w') as score:
        score.write('1000')
    print('score set')
except PermissionError:
    print('score refused')
'''


def test_the_students_processes_can_neither_signal_nor_trace_the_reaper(student):
    uid, reaper = student
    tried = as_user(uid, AGAINST_THE_REAPER % reaper.process.pid)
    assert tried.stdout.splitlines() == ['SIGKILL refused', 'SIGSTOP refused', 'SIGTERM refused', 'ptrace refused',
                                         'memory refused', 'score refused'], tried.stdout
    assert reaper.process.poll() is None
    assert reaper.kill_all(timeout=5)


def test_after_stopping_a_run_the_reaper_is_there_for_the_next(student):
    uid, reaper = student
    start_daemon(uid)
    stop_user(uid, reaper)   # after the build: the table names the reaper too (its effective user id)
    assert reaper.process.poll() is None
    assert_bomb_and_daemon_killed_at_once(uid, reaper)   # the next run forks without end


def test_a_reaper_that_could_not_drop_root_says_it_killed_nothing(student):
    uid, _ = student
    # Started by a process that is not root: it cannot take the user id, so it must not claim a kill.
    tried = as_user(uid, 'from course_common.process_table import UserReaper\n'
                         'reaper = UserReaper(%d)\nprint(reaper.kill_all(timeout=10))\nreaper.close()\n' % uid)
    assert tried.stdout == 'False\n', tried.stdout
