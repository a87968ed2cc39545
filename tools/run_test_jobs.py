#!/usr/bin/env python3
"""Runs the slow steps of ./test.sh (the rostests, the workspace pytest) a few at a time.

Usage: run_test_jobs.py --jobs N --logs DIR --times FILE --failed-steps FILE < JOBS
JOBS has one job per line: `label<TAB>exit codes that mean "ran, results written"<TAB>alone|shared
<TAB>shell command`, e.g. `rostest fake_tb3/test/rviz.test<TAB>0,1,2<TAB>shared<TAB>rostest ...`.
Each rostest starts its own master on a free port, so independent .test files may run side by side.
`alone` jobs run first, one at a time with nothing beside them: tests that measure wall-clock rates
and latencies (a 30 Hz topic's longest gap), which a second test on a 2-core machine would disturb.

Prints one line per job as it ends (label, seconds, exit status), and under a job that failed the
lines of its log that say why. Each job's whole output goes to DIR/<label>.log. The durations are
kept in FILE, so that the next run starts the longest jobs first (on a first run: in the order
given). A job that ends with any other exit status is written to --failed-steps, one per line: its
results are not to be trusted (pytest exit 5: it collected no tests).
"""
import argparse
import os
import re
import subprocess
import sys
import time

# The lines of a rostest or pytest log that say what failed.
WHY = re.compile(r'RESULT: FAIL|\[FAILURE\]|\[ERROR\] \[Testcase|^FAILED |^ERROR |Error:|'
                 r'timed out after|AssertionError|^E  ')


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
        jobs.append((label, {int(code) for code in codes.split(',')}, sharing == 'alone', command))
    return jobs


def read_times(path):
    times = {}
    try:
        with open(path) as lines:
            for line in lines:
                seconds, _, label = line.rstrip('\n').partition('\t')
                times[label] = float(seconds)
    except (OSError, ValueError):
        pass
    return times


def log_name(folder, label):
    return os.path.join(folder, re.sub(r'[^A-Za-z0-9_.-]+', '_', label) + '.log')


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--jobs', type=int, default=2)
    parser.add_argument('--logs', required=True)
    parser.add_argument('--times', required=True)
    parser.add_argument('--failed-steps', required=True)
    options = parser.parse_args()
    jobs = read_jobs(sys.stdin)
    known = read_times(options.times)
    # Those that need the machine alone first; then the longest first, so that the last minutes
    # are not one long job alone (unknown ones first of all: on a first run, the order given).
    jobs.sort(key=lambda job: (not job[2], -known.get(job[0], float('inf'))))
    os.makedirs(options.logs, exist_ok=True)
    waiting, running, failed_steps, times = list(jobs), {}, [], dict(known)
    while waiting or running:
        while waiting and len(running) < max(1, options.jobs):
            if running and (waiting[0][2] or any(entry[3] for entry in running.values())):
                break  # an `alone` job waits for the others to end, and keeps the machine to itself
            label, codes, alone, command = waiting.pop(0)
            log = open(log_name(options.logs, label), 'w')
            process = subprocess.Popen(['bash', '-c', command], stdout=log, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL)
            running[process.pid] = (process, label, codes, alone, log, time.monotonic())
        pid, status = os.wait()
        if pid not in running:
            continue
        process, label, codes, _, log, start = running.pop(pid)
        log.close()
        code = os.waitstatus_to_exitcode(status) if hasattr(os, 'waitstatus_to_exitcode') else status >> 8
        process.returncode = code
        seconds = time.monotonic() - start
        times[label] = seconds
        print('test: %s  (%.0f s%s)' % (label, seconds, '' if code == 0 else ', exit %d' % code),
              flush=True)
        if code != 0:
            with open(log_name(options.logs, label), errors='replace') as output:
                for line in output:
                    if WHY.search(line):
                        print('      ' + line.rstrip()[:300])
            print('      whole log: %s' % log_name(options.logs, label), flush=True)
        if code not in codes:
            failed_steps.append('%s (exit %d: its results cannot be trusted; log %s)'
                                % (label, code, log_name(options.logs, label)))
    with open(options.failed_steps, 'w') as out:
        out.writelines(step + '\n' for step in failed_steps)
    with open(options.times, 'w') as out:
        out.writelines('%.1f\t%s\n' % (seconds, label) for label, seconds in sorted(times.items()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
