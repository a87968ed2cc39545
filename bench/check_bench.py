#!/usr/bin/env python3
"""The student's check (`rosrun course_grader check LAB PATH`) of the course's own model solutions,
timed as a whole command, and its verdicts: each lab's check run in turn with course_grader as it
was at git revision REV ("before", its package from `git archive`, first on the Python path) and as
it is ("after"), each with nothing of the bench's beside it ("quiet") and beside a process that
keeps one core busy. Prints the medians (min - max) of the wall times and whether every run gave
the same verdicts: each criterion's pass, points and sentence (its figures left out: times and
distances measured vary from run to run). Run after `source tools/env.sh`:

    bench/check_bench.py [--before REV] [--rounds N] [--labs move_turtlebot3 ros_exercises my_turtle] [--quiet-only]

Each build's first check of a lab is a warm-up, not counted: after it, "after" builds the package in
the kept workspace of the last check (grading_session.BuildCache) as the student's next check
would; --cold empties that before each of its checks (the first check after a change to the build
description). --after-a-fix times, instead of each check, a check of a copy of the model whose first
C++ file (by name) begins with an `#error` and then the check after the student's fix (the labs
with C++ only). About 5 minutes a round of the three labs with --before."""
import argparse
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import rospkg

from course_common.processes import exit_on_terminate
from course_testing.processes import busy_core
from course_testing.verdicts import masked_figures

LABS = ('move_turtlebot3', 'ros_exercises', 'my_turtle')


def older_package(revision, folder):
    """course_grader's Python package at `revision` in `folder`; the folder to put first on the path."""
    root = subprocess.run(['git', 'rev-parse', '--show-toplevel'], stdout=subprocess.PIPE, text=True,
                          cwd=os.path.dirname(os.path.abspath(__file__)), check=True).stdout.strip()
    archive = subprocess.run(['git', 'archive', revision, 'src/course_grader/src'], stdout=subprocess.PIPE,
                             cwd=root, check=True).stdout
    subprocess.run(['tar', '-x', '-C', folder], input=archive, check=True)
    return os.path.join(folder, 'src', 'course_grader', 'src')


def verdicts(output):
    """[(criterion, passed, points, sentence without its figures)] of the check's result.json."""
    kept = re.search(r'^check: pictures and logs in (/\S+) ', output, re.M)
    if not kept:
        return [('no result', False, 0, output[-300:])]
    with open(os.path.join(kept.group(1), 'result.json')) as stream:
        result = json.load(stream)
    return [(c['id'], c['passed'], c['points'], masked_figures(c['reason'] or '')) for c in result['criteria']]


def one_check(lab, package, python_path):
    env = dict(os.environ)
    if python_path:
        env['PYTHONPATH'] = python_path + os.pathsep + env.get('PYTHONPATH', '')
    started = time.monotonic()
    done = subprocess.run(['rosrun', 'course_grader', 'check', lab, package], env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    return time.monotonic() - started, verdicts(done.stdout)


def broken_copy(package, folder):
    """A copy of the package in `folder` and its first C++ file, or (None, None) without C++."""
    copy = os.path.join(folder, 'broken', os.path.basename(package))
    shutil.copytree(package, copy, symlinks=True)
    sources = sorted(glob.glob(os.path.join(copy, 'src', '*.cpp')))
    return (copy, sources[0]) if sources else (None, None)


def checks_after_a_fix(lab, package, source, python_path):
    """The check of the package with `source` broken (a compiler error on its first line), then
    the one after the fix: [(what, seconds, verdicts)]."""
    with open(source) as stream:
        fixed = stream.read()
    with open(source, 'w') as stream:
        stream.write('#error the student\'s mistake\n' + fixed)
    failing = one_check(lab, package, python_path)
    with open(source, 'w') as stream:
        stream.write(fixed)
    after = one_check(lab, package, python_path)
    return [('fails to build', ) + failing, ('after the fix', ) + after]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--before', metavar='REV', help='course_grader at this git revision too, in turn')
    parser.add_argument('--rounds', type=int, default=2)
    parser.add_argument('--labs', nargs='+', default=list(LABS), choices=LABS)
    parser.add_argument('--quiet-only', action='store_true', help='no runs beside a busy process')
    parser.add_argument('--cold', action='store_true', help='"after" without the kept build of the last check')
    parser.add_argument('--after-a-fix', action='store_true',
                        help='a check that fails to build, then the check after the fix (C++ labs)')
    args = parser.parse_args()
    exit_on_terminate()   # a kill stops the busy process with the bench (its finally)
    src = os.path.dirname(os.path.realpath(rospkg.RosPack().get_path('course_grader')))
    cache = os.path.join(rospkg.get_ros_home(), 'course_check', '.build')
    machines = ['quiet'] + ([] if args.quiet_only else ['one busy process'])
    with tempfile.TemporaryDirectory(prefix='check_bench_') as folder:
        builds = [('after', None)]
        if args.before:
            builds.insert(0, ('before', older_package(args.before, folder)))
        times, seen = {}, {}
        for lab in args.labs:
            package, source = os.path.join(src, lab), None
            if args.after_a_fix:
                package, source = broken_copy(package, os.path.join(folder, lab))
                if package is None:
                    print('%s: no C++ file, no check after a fix' % lab, file=sys.stderr)
                    continue
            for build, path in builds:   # warm-up
                one_check(lab, package, path)
            for _ in range(args.rounds):
                for machine in machines:
                    with busy_core(machine != 'quiet'):
                        for build, path in builds:
                            if args.cold and build == 'after':
                                shutil.rmtree(os.path.join(cache, lab), ignore_errors=True)
                            checks = (checks_after_a_fix(lab, package, source, path) if source else
                                      [('',) + one_check(lab, package, path)])
                            for what, seconds, judged in checks:
                                times.setdefault((lab, machine, (build + ', ' + what).strip(', ')), []).append(seconds)
                                seen.setdefault((lab, what), set()).add(tuple(judged))
                                print('%s %s %s %s: %.1f s, %d / %d passed' % (lab, machine, build, what, seconds, sum(
                                    1 for v in judged if v[1]), len(judged)), file=sys.stderr, flush=True)
    print('rounds: %d; load average at the end %s' % (args.rounds, ' '.join('%.1f' % x for x in os.getloadavg())))
    print()
    print('| lab | machine | build | wall, median (min - max) | same verdicts in every run |')
    print('| --- | --- | --- | --: | --- |')
    for (lab, machine, build), values in times.items():
        print('| %s | %s | %s | %.1f s (%.1f - %.1f) | %s |' % (
            lab, machine, build, statistics.median(values), min(values), max(values),
            'yes' if all(len(sets) == 1 for (seen_lab, _), sets in seen.items() if seen_lab == lab) else 'NO'))
    for (lab, what), sets in seen.items():
        if len(sets) > 1:
            print('\n%s %s: the verdicts differ:' % (lab, what))
            for judged in sets:
                print('  ', judged)


if __name__ == '__main__':
    main()
