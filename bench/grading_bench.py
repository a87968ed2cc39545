#!/usr/bin/env python3
"""Grading a class: wall time of ./grade.sh for a class of generated move_turtlebot3 submissions,
in containers and without, printed as a Markdown table.

    /usr/bin/python3 bench/grading_bench.py [--students 30] [--jobs 2] [--modes container,no-container]

The class is generated from the project's own move_turtlebot3 scripts: most students correct, the
others with one of the usual mistakes (the slides' Python 2 prints, no chmod +x, another stopping
distance, another speed). Targets: the class of 30 in 4 minutes or less with containers on 2 cores;
one student alone (`--students 1 --modes container`) in 8 s or less, grade.sh's own figure per
student, from the container's start to the result. Then a table of where a correct student's time
goes, from the lines the grading writes (docs/grading.md, section 7, has the figures).
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODEL = os.path.join(ROOT, 'src', 'move_turtlebot3')
SCRIPTS = ('trajectory.py', 'laser_data.py', 'avoid_obstacle.py')
CMAKELISTS = """cmake_minimum_required(VERSION 3.0.2)
project(move_turtlebot3)
find_package(catkin REQUIRED)
catkin_package()
catkin_install_python(PROGRAMS scripts/trajectory.py scripts/laser_data.py scripts/avoid_obstacle.py
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
"""


def variant(number):
    """(name, {script: text}, executable) of generated student number `number`."""
    texts = {}
    for script in SCRIPTS:
        with open(os.path.join(MODEL, 'scripts', script)) as stream:
            texts[script] = stream.read()
    kind = number % 6
    if kind == 1:   # the slides' Python 2 print in laser_data.py
        texts['laser_data.py'] = texts['laser_data.py'].replace("print(beam(msg, 0))", "print beam(msg, 0)")
        name = 'python2_print'
    elif kind == 2:
        name = 'no_chmod'
    elif kind == 3:   # stops at another distance
        texts['avoid_obstacle.py'] = texts['avoid_obstacle.py'].replace('front > 0.5', 'front > %.2f'
                                                                        % (0.6 + 0.1 * (number % 4)))
        name = 'stops_early'
    elif kind == 4:   # another speed: another circle
        texts['trajectory.py'] = texts['trajectory.py'].replace("number_param('~linear', 1.0)",
                                                                "number_param('~linear', 0.5)")
        name = 'slow_circle'
    else:
        name = 'correct'
    return '%02d_%s' % (number, name), texts, kind != 2


def generate(folder, count):
    paths = []
    for number in range(count):
        name, texts, executable = variant(number)
        package = os.path.join(folder, name, 'move_turtlebot3')
        os.makedirs(os.path.join(package, 'scripts'))
        shutil.copy(os.path.join(MODEL, 'package.xml'), package)
        with open(os.path.join(package, 'CMakeLists.txt'), 'w') as stream:   # the three scripts only
            stream.write(CMAKELISTS)
        for script, text in texts.items():
            path = os.path.join(package, 'scripts', script)
            with open(path, 'w') as stream:
                stream.write(text)
            os.chmod(path, 0o755 if executable else 0o644)
        paths.append(os.path.join(folder, name))
    return paths


def grade(paths, out, jobs, container):
    argv = [os.path.join(ROOT, 'grade.sh'), 'move_turtlebot3'] + paths + ['--out', out, '--jobs', str(jobs)]
    if not container:
        argv.append('--no-container')
    started = time.monotonic()
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                            stdin=subprocess.DEVNULL)
    seconds = time.monotonic() - started
    if result.returncode != 0:
        print(result.stdout[-3000:], file=sys.stderr)
        raise SystemExit('grading failed (exit %d)' % result.returncode)
    with open(os.path.join(out, 'grades.csv')) as stream:
        scores = {row['student']: float(row['score']) for row in csv.DictReader(stream)}
    return seconds, scores, result.stdout


def steps(out, students):
    """{step: [seconds, one per student]} from the lines each grading wrote (grader.txt: 'built in
    1.2 s', 'trajectory.py checked in 2.0 s'), for these students."""
    found = {}
    for student in students:
        with open(os.path.join(out, student, 'grader.txt')) as stream:
            for step, seconds in re.findall(r'^grade_submission: (.+?) in ([\d.]+) s$', stream.read(), re.M):
                found.setdefault(step, []).append(float(seconds))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--students', type=int, default=30)
    parser.add_argument('--jobs', type=int, default=2)
    parser.add_argument('--modes', default='container,no-container')
    args = parser.parse_args()
    folder = tempfile.mkdtemp(prefix='grading-bench-')
    try:
        paths = generate(os.path.join(folder, 'class'), args.students)
        if 'container' in args.modes.split(','):
            # Made before the clock starts: the image is made once per change of the sources, not per class.
            subprocess.run([os.path.join(ROOT, 'grade.sh'), 'move_turtlebot3', paths[0], '--out',
                            os.path.join(folder, 'warm-up')], check=True, stdout=subprocess.DEVNULL,
                           stdin=subprocess.DEVNULL)
        rows, all_scores, breakdowns = [], [], []
        for mode in args.modes.split(','):
            out = os.path.join(folder, mode)
            seconds, scores, output = grade(paths, out, args.jobs, mode == 'container')
            all_scores.append(scores)
            wrong = sorted(name for name, score in scores.items() if name.endswith('_correct') and score != 14)
            if wrong:   # a bench of a grader that fails correct code measures nothing
                raise SystemExit('%s: correct submissions did not get 14: %s' % (mode, ', '.join(wrong)))
            # grade.sh's own figure: the gradings, without its set-up (the build's check, dockerd, the image)
            graded = re.search(r'\(([\d.]+) s per student\)', output).group(1)
            rows.append((mode, args.students, args.jobs, '%.0f' % seconds, '%.1f' % (seconds / args.students),
                         graded, '%.0f' % (sum(scores.values()) / len(scores) * 100 / 14)))
            correct = sorted(name for name in scores if name.endswith('_correct'))
            breakdowns.append((mode, len(correct), steps(out, correct)))
        print('\n### Grading a class of %d generated move_turtlebot3 submissions (%d cores)\n'
              % (args.students, os.cpu_count()))
        print('| mode | students | jobs | wall time (s) | s per student | graded, s per student | mean score (%) |')
        print('|---|---|---|---|---|---|---|')
        for row in rows:
            print('| %s |' % ' | '.join(str(cell) for cell in row))
        for mode, count, found in breakdowns:
            print('\nWhere a correct student\'s grading goes, %s (seconds, lowest to highest of %d):\n' % (mode, count))
            print('| step | seconds |')
            print('|---|---|')
            for step, values in found.items():
                print('| %s | %.1f to %.1f |' % (step, min(values), max(values)))
        if len(all_scores) == 2:
            differ = sorted(s for s in all_scores[0] if all_scores[0][s] != all_scores[1].get(s))
            print('\nSame scores in both modes: %s' % ('yes' if not differ else 'no, for ' + ', '.join(differ)))
        print('\nTargets: the class of 30 in 4 minutes (240 s) or less with containers; one student alone in 8 s '
              'or less (graded, s per student).')
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == '__main__':
    main()
