#!/usr/bin/env python3
"""Runs the slow steps of ./test.sh (the rostests, the workspace pytest) a few at a time.

Usage: run_test_jobs.py --jobs N|auto --logs DIR --times FILE [--first-times FILE] --failed-steps FILE < JOBS
JOBS has one job per line: `label<TAB>exit codes that mean "ran, results written"<TAB>alone|shared
<TAB>shell command`, e.g. `rostest fake_tb3/test/rviz.test<TAB>0,1,2<TAB>shared<TAB>rostest ...`.
Each rostest starts its own master on a free port, so independent .test files may run side by side.
`alone` jobs run first, one at a time: tests that measure wall-clock rates and latencies (a 30 Hz
topic's longest gap), which the others, free to use both cores of a 2-core machine, would disturb.
The others run beside them at a lower CPU priority (nice SHARED_NICE, which their processes
inherit) and use what it leaves (most of a core and more: an alone job mostly waits for real
time). Where nice values weigh, a process of the alone job that wakes takes a core from them at
once: within a cgroup (a container); on a host that shares the cores between sessions first
(autogroup), only among one session's processes, and roslaunch starts each node in a session of
its own, so there their nodes share the cores as equals (the rate tests hold with that too:
docs/benchmarks.md). With --jobs 1, or on a single core, nothing runs beside an alone job.
The others run N at a time; `--jobs auto` runs two, and more (up to SideBySide.AUTO_MOST) while the
cores have room for the next: over the last few seconds the cores were idle for at least that job's
share in its last run (a whole core when unknown) and HEADROOM more, and the running jobs' shares
with it fit in the cores. Most steps wait for robots moving in real time (a quarter of a core), so
on a quiet machine four or five run; on a loaded one the idle time is not there and two run, as
with --jobs 2. Once the rate steps are over, up to six, while a quarter of a core was idle, those
just started not counted against it. They start in order (the most core-seconds first): one that
computes waits for its room, and lighter ones do not pass it, unless they end before that room
comes (next_job).

Prints one line per job as it ends (label, seconds, CPU seconds of all it ran, exit status), and
under a job that failed the lines of its log that say why. Each job's whole output goes to
DIR/<label>.log, and when each ran to DIR/timeline.txt. The durations are
kept in FILE (`wall seconds<TAB>CPU seconds<TAB>label`), so that the next run starts the jobs of the most core-seconds first (on a first run, those of
--first-times, measured once on a 2-core machine; jobs unknown to both come first). A job that ends
with any other exit status is written to --failed-steps, one per line: its results are not to be
trusted (a pytest job's exit 5: it collected no tests). So is a job that leaves processes running: each job's
environment carries a mark of its own, and what still carries it a few seconds after the job ended
(a node in a session of its own, reparented to init, that no process group reaches) is named, then
killed.
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import time

from course_common.process_table import command_line, marked_processes, new_mark, stop_marked, with_mark
from course_common.processes import restore_ctrl_c
from course_common.waiting import poll_until

# The nice value of the shared jobs: an alone job's process (nice 0) that wakes takes the core from
# them at once, and gets 9 times their share of a core both want (nice 19 would give 68 times, but
# would starve them beside any busy process of the same session, as idle priority did).
SHARED_NICE = 10
# The least share of a core a shared job is taken to use beyond the first two (SideBySide.spare).
LIGHTEST_SHARE = 0.25
# Beside a rate step, the share of a core left idle when a job beyond the first two starts: their
# shares are averages. Without it, and with the shares planned half a core beyond the cores, six steps
# ran beside tests/network/test_simulator_abuse.py in CI on 2026-12-05, and turtlesim's 62.5 Hz pose
# came at 53 Hz (on a host, roslaunch's nodes each have a session of their own: nice does not weigh).
HEADROOM = 0.25
# The lines of a rostest or pytest log that say what failed.
WHY = re.compile(r'RESULT: FAIL|\[FAILURE\]|\[ERROR\] \[Testcase|^FAILED |^ERROR |Error:|'
                 r'timed out after|AssertionError|^E  ')


# A step of the list: its label, the exit codes after which its result file tells the rest, whether
# it runs alone (it measures wall-clock rates), its shell command.
Job = collections.namedtuple('Job', 'label codes alone command')
# A step that runs: its Popen, the Job's fields, its log file, its time.monotonic() start, the mark
# in its environment.
Running = collections.namedtuple('Running', 'process label codes alone log start mark')


def read_jobs(stream):
    jobs = []
    for number, line in enumerate(stream, 1):
        if not line.strip():
            continue
        fields = line.rstrip('\n').split('\t')
        if len(fields) != 4 or fields[2] not in ('alone', 'shared'):
            raise SystemExit('run_test_jobs: line %d is not label<TAB>codes<TAB>alone|shared<TAB>command'
                             % number)
        label, codes, sharing, command = fields
        jobs.append(Job(label, {int(code) for code in codes.split(',')}, sharing == 'alone', command))
    return jobs


def read_times(path):
    """{label: (wall seconds, CPU seconds or None)} from a file of `wall<TAB>CPU<TAB>label` lines
    (or `wall<TAB>label`, the older form, without CPU)."""
    times = {}
    try:
        with open(path) as lines:
            for line in lines:
                if line.startswith('#'):
                    continue
                fields = line.rstrip('\n').split('\t')
                cpu = None if len(fields) == 2 or fields[1] == '-' else float(fields[1])
                times[fields[-1]] = (float(fields[0]), cpu)
    except (OSError, ValueError, IndexError):
        pass
    return times


def cpu_share(times, label):
    """The share of one core a job used in its last run (CPU over wall seconds), None if unknown."""
    seconds, cpu = times.get(label, (None, None))
    return cpu / seconds if cpu is not None and seconds else None


def reserved(times, label):
    """The core-seconds a job holds: its wall seconds times what it is taken to use of a core
    (needs), infinite when unknown. A job that waits (a quarter of a core for 98 s) comes after one
    that computes for 65 s: put first by its wall time, it held one of the first two places while
    the computing job waited for room beside it, the cores half idle (70 s in a run of 2026-12-04)."""
    if label not in times:
        return float('inf')
    seconds, _ = times[label]
    return seconds * needs(cpu_share(times, label))


def cpu_sample(stat='/proc/stat'):
    """(idle, total) jiffies of all cores together, from the first line of /proc/stat."""
    with open(stat) as lines:
        fields = [int(value) for value in lines.readline().split()[1:]]
    idle = fields[3] + (fields[4] if len(fields) > 4 else 0)  # idle + iowait
    return idle, sum(fields[:8])  # guest times are already inside user and nice


def idle_cores(before, after, cores):
    """How many cores were idle, on average, between two cpu_sample()s."""
    total = after[1] - before[1]
    return cores * (after[0] - before[0]) / total if total > 0 else 0.0


class SideBySide:
    """How much of the cores one more shared job may use now: any while fewer than `jobs` run; with
    jobs='auto', once two run, what both the cores' idle time over the last `window` seconds (less
    what the jobs started within them are taken to use: their start is not in it yet) and the
    running jobs' shares (from their last run) leave, up to AUTO_MOST jobs. Once the rate steps are
    over, up to AUTO_MOST_AFTER_RATES, each while a quarter of a core was idle over the window,
    the jobs started within it not counted against that: nothing measures wall-clock rates any
    more, so a core that gets more than it can do only stretches the steps on it, which every step
    holds with (a busy core beside it); the shares planned, averages, held a job back (the cores
    idle a fifth of the time after the rate steps), and so did each start counted for a whole
    window (at most one start in 3 s: 3 steps of 10 s side by side where six could run, the cores
    a fifth idle again, 2026-12-05). Where the idle time is not there (a loaded machine), two run."""
    AUTO, AUTO_MOST, AUTO_MOST_AFTER_RATES = 2, 5, 6

    def __init__(self, jobs, cores, window=3.0, sample=cpu_sample, clock=time.monotonic):
        self.auto = jobs == 'auto'
        self.jobs = self.AUTO if self.auto else max(1, jobs)
        self.cores, self.window, self.sample, self.clock = cores, window, sample, clock
        self.samples = collections.deque([(clock(), sample())])   # (time, cpu_sample())
        self.starts = collections.deque()                          # (time, what it is taken to use)

    def started(self, share=None):
        """A job started, which used `share` of a core in its last run (None: unknown)."""
        self.starts.append((self.clock(), needs(share)))

    def idle(self):
        """How many cores were idle over the last `window` seconds, or None before that long."""
        now = self.clock()
        self.samples.append((now, self.sample()))
        while len(self.samples) > 2 and now - self.samples[1][0] >= self.window:
            self.samples.popleft()
        if now - self.samples[0][0] < self.window:
            return None
        return idle_cores(self.samples[0][1], self.samples[-1][1], self.cores)

    def beside(self, running):
        """Whether an alone job may start beside `running` shared jobs (of a lower priority)."""
        return running == 0 or (self.cores > 1 and (self.auto or running < self.jobs))

    def spare(self, shares, rates_done=False):
        """The share of a core the next shared job may use (float('inf'): any); `shares`: the running
        jobs' shares of a core in their last run (None: unknown, taken as a whole core);
        `rates_done`: no rate step runs or waits."""
        if len(shares) < self.jobs:
            return float('inf')
        if not self.auto or len(shares) >= (self.AUTO_MOST_AFTER_RATES if rates_done else self.AUTO_MOST):
            return 0.0
        idle = self.idle()
        if idle is None:
            return 0.0
        if rates_done:
            return float('inf') if idle >= LIGHTEST_SHARE else 0.0
        while self.starts and self.clock() - self.starts[0][0] >= self.window:
            self.starts.popleft()
        left = idle - sum(uses for _, uses in self.starts)
        planned = self.cores - sum(needs(share) for share in shares)
        return min(left - HEADROOM, planned)


def needs(share):
    """What a job is taken to use of a core, from its share in its last run: a whole core when
    unknown, and never less than LIGHTEST_SHARE (its start, a master and nodes, is busier)."""
    return 1.0 if share is None else max(share, LIGHTEST_SHARE)


def room_comes(running, needed, cores, share, wall):
    """When (a time of SideBySide's clock) the running jobs leave `needed` of a core planned for
    another, as each ends after its wall seconds of its last run; None when it is there already,
    or when a job that must end first is of unknown length."""
    room = cores - sum(needs(share(entry.label)) for entry in running)
    if room >= needed:
        return None
    ends = sorted((entry.start + (wall(entry.label) or float('inf')), needs(share(entry.label)))
                  for entry in running)
    for end, freed in ends:
        room += freed
        if room >= needed:
            return end if end < float('inf') else None
    return None


def next_job(waiting, running, side_by_side, share=lambda label: None, wall=lambda label: None):
    """The index in `waiting` (Jobs, the alone ones first) of the job to start now, or None when
    none may start yet. `running`: the Running jobs; `share(label)`: a job's share of a core in its
    last run, `wall(label)` its wall seconds (None if unknown). An alone job starts when no other
    alone job runs (the others run at a lower priority; with --jobs 1 or on one core, when nothing
    runs), a shared one when the cores have room for it beside all that runs, the alone job included
    (SideBySide), in order: a computing job that waits for room is not passed by lighter ones, which
    would keep the room from coming and leave it for the end, alone. Unless the room it waits for is
    held by running jobs that end later (the ros_exercises page, a whole core for 65 s, beside a
    rate step: the next that computes waited with the cores a third idle): then a later one that
    fits now and ends before that room comes starts (backfilling, as batch schedulers do), and
    delays nothing."""
    running = list(running)
    shares = [share(entry.label) for entry in running]
    alone_runs = any(entry.alone for entry in running)
    first_alone = next((index for index, job in enumerate(waiting) if job.alone), None)
    if first_alone is not None and not alone_runs:
        # Nothing passes an alone job that waits for the others to end.
        return first_alone if side_by_side.beside(len(running)) else None
    if alone_runs and not side_by_side.beside(len(running)):
        return None
    first_shared = next((index for index, job in enumerate(waiting) if not job.alone), None)
    if first_shared is None:
        return None
    # Here an alone job runs, or none waits.
    spare = side_by_side.spare(shares, rates_done=not alone_runs)
    needed = needs(share(waiting[first_shared].label))
    if needed <= spare:
        return first_shared
    comes = room_comes(running, needed, side_by_side.cores, share, wall)
    if comes is None:
        return None
    now = side_by_side.clock()
    return next((index for index in range(first_shared + 1, len(waiting))
                 if not waiting[index].alone and wall(waiting[index].label) is not None
                 and needs(share(waiting[index].label)) <= spare
                 and now + wall(waiting[index].label) <= comes), None)


def start_job(alone):
    """In the job's process before it runs its command: Ctrl-C as in a terminal, and a shared job's
    lower priority."""
    restore_ctrl_c()
    if not alone:
        os.setpriority(os.PRIO_PROCESS, 0, max(SHARED_NICE, os.getpriority(os.PRIO_PROCESS, 0)))


def left_running(mark, grace=5.0):
    """What still runs with `mark` in its environment once `grace` seconds have passed (a node may
    still be saving its picture as its roslaunch ends), as command lines, each on one line (a
    `python3 -c` program's lines would each count as a failed step); then stops it."""
    poll_until(lambda: not marked_processes(mark), grace, poll=0.2)
    left = [command_line(pid).replace('\n', '\\n') for pid in marked_processes(mark)]
    stop_marked(mark)
    return left


def log_name(folder, label):
    return os.path.join(folder, re.sub(r'[^A-Za-z0-9_.-]+', '_', label) + '.log')


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--jobs', default='auto', type=lambda value: value if value == 'auto' else int(value))
    parser.add_argument('--logs', required=True)
    parser.add_argument('--times', required=True)
    parser.add_argument('--first-times')
    parser.add_argument('--failed-steps', required=True)
    options = parser.parse_args()
    jobs = read_jobs(sys.stdin)
    known = read_times(options.first_times) if options.first_times else {}
    known.update(read_times(options.times))
    # Those that need the machine alone first; then the most core-seconds first (unknown ones first
    # of all), so that the last minutes are not one long job alone.
    jobs.sort(key=lambda job: (not job.alone, -reserved(known, job.label)))
    os.makedirs(options.logs, exist_ok=True)
    side_by_side = SideBySide(options.jobs, len(os.sched_getaffinity(0)))
    widest = 0
    waiting, running, failed_steps, times = list(jobs), {}, [], dict(known)
    # When each step ran, in seconds from here (how the steps were packed: docs/testing.md).
    began = time.monotonic()
    timeline = open(os.path.join(options.logs, 'timeline.txt'), 'w')
    timeline.write('# start\tend\tCPU seconds\tstep (from the first start)\n')
    while waiting or running:
        while waiting:
            index = next_job(waiting, running.values(), side_by_side,
                             share=lambda label: cpu_share(known, label),
                             wall=lambda label: known.get(label, (None,))[0])
            if index is None:
                break
            job = waiting.pop(index)
            log = open(log_name(options.logs, job.label), 'w')
            mark = new_mark('COURSE_TEST_STEP')
            # SIGINT and SIGQUIT as in a terminal: when test.sh runs in the background (`./test.sh &`,
            # a CI runner), every program inherits both ignored, and the tests' roscore and roslaunch
            # would ignore the SIGINT that stops them (tests/network/ took 181 s instead of 90).
            process = subprocess.Popen(['bash', '-c', job.command], stdout=log, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL, env=with_mark(mark),
                                       preexec_fn=lambda alone=job.alone: start_job(alone))
            running[process.pid] = Running(process, job.label, job.codes, job.alone, log, time.monotonic(),
                                           mark)
            side_by_side.started(cpu_share(known, job.label))
            widest = max(widest, len(running))
        # With jobs waiting for an idle core, look again every half second.
        pid, status, usage = os.wait4(-1, os.WNOHANG if side_by_side.auto and waiting else 0)
        if pid == 0:
            time.sleep(0.5)
            continue
        if pid not in running:
            continue
        ended = running.pop(pid)
        process, label, codes, log, start, mark = (ended.process, ended.label, ended.codes, ended.log,
                                                   ended.start, ended.mark)
        log.close()
        code = os.waitstatus_to_exitcode(status) if hasattr(os, 'waitstatus_to_exitcode') else status >> 8
        process.returncode = code
        seconds = time.monotonic() - start
        left = left_running(mark)
        # The CPU time of the step and of every process it waited for (roslaunch's nodes included).
        cpu = usage.ru_utime + usage.ru_stime
        times[label] = (seconds, cpu)
        timeline.write('%.1f\t%.1f\t%.1f\t%s\n' % (start - began, start - began + seconds, cpu, label))
        timeline.flush()
        print('test: %s  (%.0f s, %.0f s CPU%s)' % (label, seconds, cpu,
                                                   '' if code == 0 else ', exit %d' % code), flush=True)
        if code != 0:
            with open(log_name(options.logs, label), errors='replace') as output:
                for line in output:
                    if WHY.search(line):
                        print('      ' + line.rstrip()[:300])
            print('      whole log: %s' % log_name(options.logs, label), flush=True)
        if code not in codes and code == 5 and label.startswith('pytest '):
            failed_steps.append('%s collected no tests (exit 5)' % label)
        elif code not in codes:
            failed_steps.append('%s (exit %d: its results cannot be trusted; log %s)'
                                % (label, code, log_name(options.logs, label)))
        if left:
            for line in left:
                print('      left running: ' + line[:300])
            failed_steps.append('%s left %d process%s running (killed now): %s'
                                % (label, len(left), '' if len(left) == 1 else 'es', '; '.join(left)[:1000]))
    timeline.close()
    print('test: at most %d steps ran side by side' % widest, flush=True)
    with open(options.failed_steps, 'w') as out:
        out.writelines(step + '\n' for step in failed_steps)
    with open(options.times, 'w') as out:
        out.writelines('%.1f\t%s\t%s\n' % (seconds, '-' if cpu is None else '%.1f' % cpu, label)
                       for label, (seconds, cpu) in sorted(times.items()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
