#!/usr/bin/env python3
"""The student's check (`rosrun course_grader check LAB PATH`) of the course's own model solutions,
timed as a whole command, and its verdicts: each lab's check run in turn with the workspace as it
was at git revision REV ("before": the whole tree from `git archive`, built by tools/setup.sh in a
folder of the bench's, about a minute) and as it is ("after"), each with nothing of the bench's
beside it ("quiet") and beside a process that keeps one core busy. Each build has a ROS_HOME of its
own in the bench's folder (its checks and its kept builds). Prints the medians (min - max) of the
wall times and whether every run gave the same verdicts: each criterion's pass, points and sentence
(its figures left out: times and distances measured vary from run to run). Run after `source tools/env.sh`:

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


def older_workspace(revision, folder):
    """The environment of the workspace at `revision`, built in `folder`/before (its devel sourced)."""
    root = subprocess.run(['git', 'rev-parse', '--show-toplevel'], stdout=subprocess.PIPE, text=True,
                          cwd=os.path.dirname(os.path.abspath(__file__)), check=True).stdout.strip()
    tree = os.path.join(folder, 'before')
    os.makedirs(tree)
    archive = subprocess.run(['git', 'archive', revision], stdout=subprocess.PIPE, cwd=root, check=True).stdout
    subprocess.run(['tar', '-x', '-C', tree], input=archive, check=True)
    built = subprocess.run([os.path.join(tree, 'tools', 'setup.sh')], env=dict(os.environ, COURSE_SKIP_INSTALL='1'),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if built.returncode != 0:
        sys.exit('check_bench: the workspace at %s does not build:\n%s' % (revision, built.stdout[-2000:]))
    listing = subprocess.run(['bash', '-c', 'source "$1/tools/env.sh" && env -0', 'env', tree],
                             stdout=subprocess.PIPE, check=True).stdout
    return dict(entry.split('=', 1) for entry in listing.decode().split('\0') if '=' in entry)


def verdicts(output):
    """[(criterion, passed, points, sentence without its figures)] of the check's result.json."""
    kept = re.search(r'^check: pictures and logs in (/\S+) ', output, re.M)
    if not kept:
        return [('no result', False, 0, output[-300:])]
    with open(os.path.join(kept.group(1), 'result.json')) as stream:
        result = json.load(stream)
    return [(c['id'], c['passed'], c['points'], masked_figures(c['reason'] or '')) for c in result['criteria']]


def one_check(lab, package, env):
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


def checks_after_a_fix(lab, package, source, env):
    """The check of the package with `source` broken (a compiler error on its first line), then
    the one after the fix: [(what, seconds, verdicts)]."""
    with open(source) as stream:
        fixed = stream.read()
    with open(source, 'w') as stream:
        stream.write('#error the student\'s mistake\n' + fixed)
    failing = one_check(lab, package, env)
    with open(source, 'w') as stream:
        stream.write(fixed)
    after = one_check(lab, package, env)
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
    machines = ['quiet'] + ([] if args.quiet_only else ['one busy process'])
    with tempfile.TemporaryDirectory(prefix='check_bench_') as folder:
        builds = [('after', dict(os.environ))]
        if args.before:
            builds.insert(0, ('before', older_workspace(args.before, folder)))
        for build, env in builds:
            env['ROS_HOME'] = os.path.join(folder, build + '_ros_home')
        times, seen = {}, {}
        for lab in args.labs:
            package, source = os.path.join(src, lab), None
            if args.after_a_fix:
                package, source = broken_copy(package, os.path.join(folder, lab))
                if package is None:
                    print('%s: no C++ file, no check after a fix' % lab, file=sys.stderr)
                    continue
            for build, env in builds:   # warm-up
                one_check(lab, package, env)
            for _ in range(args.rounds):
                for machine in machines:
                    with busy_core(machine != 'quiet'):
                        for build, env in builds:
                            if args.cold and build == 'after':
                                shutil.rmtree(os.path.join(env['ROS_HOME'], 'course_check', '.build', lab),
                                              ignore_errors=True)
                            checks = (checks_after_a_fix(lab, package, source, env) if source else
                                      [('',) + one_check(lab, package, env)])
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
