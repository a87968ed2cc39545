"""The processes of this machine, read from /proc: found by their parent, their user or a mark in
their environment, and stopped.

A mark (NAME=value, the value new each time) put into the environment of what a program starts is
inherited by everything that starts in turn, wherever it goes: roslaunch starts each node in a
session of its own, and a node whose roslaunch has gone is reparented to init, where neither a
process group nor a walk down from the parent finds it. Its environment still carries the mark.

A chroot has no /proc of its own (Gradescope's, which needs a privilege to mount one): the process
that enters it can hand down /proc opened as a folder, its descriptor's number in PROC_FD_VARIABLE
(platforms/gradescope/run_autograder); without either, there is no telling which processes live.
"""
import functools
import os
import select
import signal
import subprocess
import sys
import time
import uuid

PROC = '/proc'
PROC_FD_VARIABLE = 'COURSE_PROC_FD'


class NoProcessTable(OSError):
    """Neither /proc nor a descriptor of it handed down: no process can be found."""


def proc_fd():
    """The descriptor of /proc handed down in PROC_FD_VARIABLE, or None (then PROC is read)."""
    value = os.environ.get(PROC_FD_VARIABLE)
    return int(value) if value else None


def process_ids():
    """The ids of the processes living now; NoProcessTable where there is no /proc to read them from
    (a chroot's /proc is an empty folder or none)."""
    fd = proc_fd()
    try:
        names = os.listdir(PROC if fd is None else fd)
    except OSError as error:
        names = [error.strerror or str(error)]
    if 'self' not in names:
        raise NoProcessTable('no process table here: %s is not mounted (a chroot\'s is not) and %s names no '
                             'descriptor of one' % (PROC, PROC_FD_VARIABLE))
    return [int(name) for name in names if name.isdigit()]


def _read(pid, name):
    """/proc/PID/NAME's bytes; None once the process has gone (or if it is not ours to read)."""
    return _read_proc('%d/%s' % (pid, name))


def _read_proc(relative):
    """/proc/RELATIVE's bytes; None if there is none (or if it is not ours to read)."""
    fd = proc_fd()
    path = relative if fd is not None else '%s/%s' % (PROC, relative)
    try:
        with open(path, 'rb', opener=functools.partial(os.open, dir_fd=fd)) as stream:
            return stream.read()
    except OSError:
        return None


def listening_sockets(port):
    """The inodes of the TCP sockets listening on `port` (on any address, IPv4 or IPv6) in this
    network namespace; NoProcessTable where there is no /proc to read them from."""
    ipv4 = _read_proc('net/tcp')
    if ipv4 is None:
        raise NoProcessTable('no process table here to read net/tcp from')
    inodes = set()
    for table in (ipv4, _read_proc('net/tcp6') or b''):   # no tcp6 without IPv6
        for line in table.splitlines()[1:]:
            fields = line.split()   # sl local_address rem_address st ... uid timeout inode
            if len(fields) > 9 and fields[3] == b'0A' and int(fields[1].rsplit(b':', 1)[1], 16) == port:
                inodes.add(int(fields[9]))
    return inodes


def socket_inodes(pid):
    """The inodes of the sockets `pid` holds open: empty once it has gone (or if it is not ours to read)."""
    fd = proc_fd()
    try:
        folder = os.open('%d/fd' % pid if fd is not None else '%s/%d/fd' % (PROC, pid),
                         os.O_RDONLY | os.O_DIRECTORY, dir_fd=fd)
    except OSError:
        return set()
    inodes = set()
    try:
        for name in os.listdir(folder):
            try:
                target = os.readlink(name, dir_fd=folder)
            except OSError:   # closed meanwhile
                continue
            if target.startswith('socket:['):
                inodes.add(int(target[len('socket:['):-1]))
    finally:
        os.close(folder)
    return inodes


def parent_of(pid):
    """The id of the parent of `pid`; None once it has gone."""
    stat = _read(pid, 'stat')
    try:
        return int(stat.rsplit(b')', 1)[1].split()[1])   # the command's name may hold ') '
    except (AttributeError, IndexError, ValueError):
        return None


def descendants(pid):
    """The ids of every living process below `pid` (its children, theirs, ...), at the time of the call."""
    children = {}
    for child in process_ids():
        children.setdefault(parent_of(child), []).append(child)
    found, frontier = [], [pid]
    while frontier:
        below = children.get(frontier.pop(), [])
        found.extend(below)
        frontier.extend(below)
    return found


def user_processes(uid):
    """The ids of the live processes (not zombies) of the user `uid`."""
    found = []
    for pid in process_ids():
        status = _read(pid, 'status')
        if status is None:
            continue
        fields = dict(line.split(':', 1) for line in status.decode(errors='replace').splitlines() if ':' in line)
        if str(uid) in fields.get('Uid', '').split() and not fields.get('State', '').strip().startswith('Z'):
            found.append(pid)
    return found


def new_mark(name):
    """A mark NAME=value, the value new: for the environment of what a program starts."""
    return '%s=%s' % (name, uuid.uuid4().hex)


def with_mark(mark, env=None):
    """A copy of `env` (default os.environ) that carries `mark`."""
    name, value = mark.split('=', 1)
    return dict(os.environ if env is None else env, **{name: value})


def marked_processes(mark):
    """The ids of the live processes whose environment carries `mark` (NAME=value), this one excepted."""
    needle = mark.encode()
    return [pid for pid in process_ids()
            if pid != os.getpid() and needle in (_read(pid, 'environ') or b'').split(b'\0')]


def command_line(pid):
    """'PID the command line' of a process, for a message ('PID (gone)' once it has gone)."""
    command = _read(pid, 'cmdline')
    if command is None:
        return '%d (gone)' % pid
    return '%d %s' % (pid, command.rstrip(b'\0').replace(b'\0', b' ').decode(errors='replace'))


def stop_processes(find, seconds=5.0):
    """SIGKILL every process `find()` names (this one excepted), again until it names none (one may
    fork meanwhile) or `seconds` have passed. Returns how many were stopped, each counted once (a
    killed one may be found again while it exits). It looks again after 5 ms, then twice as long
    each time up to 0.1 s: most are gone within milliseconds."""
    stopped = set()
    deadline = time.monotonic() + seconds
    pause = 0.005
    while True:
        found = [pid for pid in find() if pid != os.getpid()]
        if not found or time.monotonic() > deadline:
            break
        for pid in found:
            try:
                os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        stopped.update(found)
        time.sleep(pause)
        pause = min(2 * pause, 0.1)
    return len(stopped)


def stop_marked(mark):
    """SIGKILL every process whose environment carries `mark`; returns how many were stopped."""
    return stop_processes(lambda: marked_processes(mark))


def stop_user(uid, reaper=None):
    """SIGKILL every process of the user `uid` (the student's side in a sandbox): all at once by the
    user's `reaper` (a UserReaper) when there is one, then each one the process table still names;
    returns how many the table named. Where there is no process table, says so on standard error
    (the grading's log) and stops none but the reaper's: the grading goes on, but what the
    student's side left running may live on. The reaper itself is left alive for the next time:
    its effective user id is the user's, so the table names it too."""
    if reaper is not None:
        reaper.kill_all()
    spared = reaper.process.pid if reaper is not None else None
    try:
        return stop_processes(lambda: [pid for pid in user_processes(uid) if pid != spared])
    except NoProcessTable as error:
        print('process_table: the processes of user %d cannot be stopped: %s. Whatever they started '
              '(a daemon of the build) goes on running.' % (uid, error), file=sys.stderr, flush=True)
        return 0


# The reaper's program: it drops root for good, its real and saved ids `nobody`'s and its effective
# user id the student's, then kills every process of that user (kill(-1): one system call, which no
# fork can race) each time a byte comes, again until none is left running, and answers with a byte.
# A process killed runs on until it has exited, longer on a busy machine: the reaper answers once
# the process table names none (zombies aside), or after 10 s; where there is no table to read,
# after a thousand kills.
REAPER = r"""
import os, signal, sys, time
sys.path.insert(0, PACKAGES)
from course_common.process_table import NoProcessTable, user_processes
os.setgroups([])
os.setresgid(NOBODY, NOBODY, NOBODY)
os.setresuid(NOBODY, UID, NOBODY)

def running():
    try:
        return [pid for pid in user_processes(UID) if pid != os.getpid()]
    except NoProcessTable:
        return []

while sys.stdin.buffer.read(1):
    deadline = time.monotonic() + 10
    for kills in range(1000000):
        try:
            os.kill(-1, signal.SIGKILL)
        except ProcessLookupError:
            break
        if kills >= 1000:
            if not running() or time.monotonic() > deadline:
                break
            time.sleep(0.001)
    sys.stdout.buffer.write(b'.')
    sys.stdout.flush()
"""
NOBODY = 65534


class UserReaper:
    """Kills every process of the user `uid` at once, even a fork bomb that holds every process its
    sandbox allows (then no program could start to stop it) and that scanning /proc would never
    catch up with (a process that forks and leaves). Started before the user has any process, by
    root (with the capability to change user ids): a process of `uid` may be signalled only by it,
    and may neither signal nor trace the reaper (whose real and saved user is nobody)."""

    def __init__(self, uid):
        packages = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))   # where course_common is
        program = REAPER.replace('NOBODY', str(NOBODY)).replace('UID', str(uid)).replace('PACKAGES', repr(packages))
        self.process = subprocess.Popen([sys.executable, '-c', program], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, start_new_session=True)

    def kill_all(self, timeout=30.0):
        """True once every process of the user was killed (the reaper answered within `timeout`)."""
        try:
            self.process.stdin.write(b'k')
            self.process.stdin.flush()
        except OSError:
            return False   # the reaper has gone
        ready, _, _ = select.select([self.process.stdout], [], [], timeout)
        return bool(ready) and self.process.stdout.read(1) == b'.'

    def close(self):
        self.process.kill()
        self.process.wait()
