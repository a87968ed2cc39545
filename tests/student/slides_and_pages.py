"""Slides + pages = full marks, what each lab's test shares (test_pages_<lab>.py, a step of ./test.sh
each). A student pastes each lab's code from the seeds (slides/pasted/: what a paste gives, damage
included) or types it as printed (slides/), meets the errors docs/copying-the-slides/ quotes (each
quoted line must be on the page, exactly as this machine prints it), applies only the edits the
pages prescribe, and hands the package in: `rosrun course_grader grade LAB PACKAGE --no-container`
(what ./grade.sh runs after its set-up) must give full marks, and the student's own check (`rosrun
course_grader check LAB --only ID`) must find the student's package and pass.

The terminals are test_student_workspace's: nothing but HOME, a PATH whose first python has no
rospy, and the student's devel/setup.bash."""
import csv
import os
import re
import shutil
from concurrent.futures import ThreadPoolExecutor

from course_common.process_table import command_line, marked_processes, new_mark, stop_marked
from test_student_workspace import COURSE_DEVEL, ROOT, SLIDES

PASTED = os.path.join(SLIDES, 'pasted')
PAGES = os.path.join(ROOT, 'docs', 'copying-the-slides')


def page(lab):
    with open(os.path.join(PAGES, lab + '.md')) as text:
        return text.read()


def slide(name, folder=SLIDES):
    with open(os.path.join(folder, name)) as text:
        return text.read()


def quoted(student, output, pattern, lab):
    """The first output line matching `pattern`, with the student's home written /home/you as the
    pages write it; it must be on the lab's copying page, exactly."""
    lines = [line.replace(student.home, '/home/you') for line in output.splitlines()
             if re.search(pattern, line)]
    assert lines, 'no line matching %r in:\n%s' % (pattern, output[-3000:])
    assert lines[0] in page(lab), '%s.md does not quote %r' % (lab, lines[0])
    return lines[0]


def make_package(student, command, package):
    """catkin_create_pkg, then `rospack find` must name the student's own copy (the page's check)."""
    status, output = student.run('cd src && %s && rospack profile > /dev/null && rospack find %s' % (command, package))
    assert status == 0, output
    assert output.splitlines()[-1] == os.path.join(student.workspace, 'src', package), output


def run_leaving_nothing(student, command, **options):
    """student.run(command), which must leave nothing running once it has ended (roslaunch's nodes
    included, in sessions of their own: found by a mark in the environment the command starts with)."""
    mark = new_mark('COURSE_STUDENT_TEST')
    try:
        status, output = student.run('export %s; %s' % (mark, command), **options)
    finally:
        left = [command_line(pid) for pid in marked_processes(mark)]
        stop_marked(mark)
    assert left == [], 'still running after %s: %s' % (command, left)
    return status, output


def grade(student, lab):
    """The teacher's grading of the student's package, on this machine: (score, max, the report's row)."""
    out = os.path.join(student.home, 'grades-' + lab)
    status, output = run_leaving_nothing(
        student, 'source %s/setup.bash && rosrun course_grader grade %s %s --no-container --out %s'
        % (COURSE_DEVEL, lab, os.path.join(student.workspace, 'src', lab), out), timeout=900, source=False)
    assert status == 0, output[-3000:]
    print(output[-600:])   # the grader's lines, for pytest -s
    with open(os.path.join(out, 'grades.csv')) as table:
        row = next(csv.DictReader(table))
    return int(float(row['score'])), int(float(row['max_score'])), row, output


def check(student, lab, *options):
    """The student's own check, in the student's terminal (the overlay's package, found by rospack):
    the package it names and the lines it ends with."""
    status, output = run_leaving_nothing(student, 'rosrun course_grader check %s %s' % (lab, ' '.join(options)),
                                         timeout=900)
    kept = re.search(r'^check: pictures and logs in (/\S+)$', output, re.M)
    if kept:   # a folder of the check's own in /tmp
        shutil.rmtree(os.path.dirname(kept.group(1)))
    assert status == 0, output[-3000:]
    print(output[-1500:])
    package = os.path.join(student.workspace, 'src', lab)
    assert 'check: grading the package at %s with the rubric of %s' % (package, lab) in output, output
    assert re.search(r'^check: built in [0-9.]+ s$', output, re.M), output   # each step with its time
    assert output.rstrip().endswith("check: This is your own check: the teacher's run, in a container, "
                                    "is the one that counts."), output[-500:]
    return output


def full_marks_then_checked(student, lab, full, criterion):
    """The teacher's grading gives full marks, and the student's check of one criterion (the
    grading proves the others) passes it; the two run side by side, as in two terminals (each
    builds the package and waits for simulators). Returns what the check printed."""
    with ThreadPoolExecutor(max_workers=1) as pool:
        checking = pool.submit(check, student, lab, '--only', criterion)
        score, most, row, output = grade(student, lab)
        assert (score, most) == (full, full), (row, output[-2000:])
        output = checking.result()
    assert re.findall(r'^(PASS|FAIL) (\S+)', output, re.M) == [('PASS', criterion)], output[-2000:]
    assert re.search(r'^check: %s (\d+) / \1, the other criteria not checked \(\d+ s\)$' % criterion, output,
                     re.M), output
    return output
