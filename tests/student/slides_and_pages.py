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
from concurrent.futures import ThreadPoolExecutor

from course_common.process_table import command_line, marked_processes, new_mark, stop_marked
from course_testing.markdown import headings
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


def check(student, lab, *options, built=True):
    """The student's own check, in the student's terminal (the overlay's package, found by rospack):
    the package it names and the lines it ends with (and the build's time, when it built)."""
    status, output = run_leaving_nothing(student, 'rosrun course_grader check %s %s' % (lab, ' '.join(options)),
                                         timeout=900)
    assert status == 0, output[-3000:]
    # Kept in the student's own ~/.ros, where the browser view shows it (course_web.last_check).
    kept = re.search(r'^check: pictures and logs in (/\S+) \(the last 5 checks of each lab are kept\)$', output, re.M)
    assert kept and kept.group(1).startswith(os.path.join(student.home, '.ros', 'course_check', lab, '')), output[-3000:]
    assert os.path.isfile(os.path.join(os.path.dirname(kept.group(1)), 'check.json')), kept.group(1)
    print(output[-1500:])
    package = os.path.join(student.workspace, 'src', lab)
    assert 'check: grading the package at %s with the rubric of %s' % (package, lab) in output, output
    assert bool(re.search(r'^check: built in [0-9.]+ s$', output, re.M)) == built, output   # each step with its time
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


def section(page_path, anchor):
    """The text of the section of a page (docs/...) whose heading has that anchor, down to the next
    heading of its level or above; it must be there."""
    with open(os.path.join(ROOT, page_path)) as text:
        lines = text.read().split('\n')
    found = headings('\n'.join(lines))
    anchors = [name for _, _, name in found]
    assert anchor in anchors, '%s has no section #%s (its anchors: %s)' % (page_path, anchor, anchors)
    start, level, _ = found[anchors.index(anchor)]
    end = next((number for number, depth, _ in found if number > start and depth <= level), len(lines))
    return '\n'.join(lines[start:end])


def criteria_printed(output):
    """{criterion id: (PASS or FAIL, what the check printed under it)} of a check's output."""
    blocks = re.split(r'^(?=PASS |FAIL |---- |check: )', output, flags=re.M)
    found = {}
    for block in blocks:
        head = re.match(r'(PASS|FAIL) (\S+)', block)
        if head:
            found[head.group(2)] = (head.group(1), block)
    return found


def check_names_the_sections(student, lab, sections, built=True):
    """The student's check of the package as the paste left it: each criterion it fails names the
    section of the pages that explains why, or was not run because of another criterion. sections:
    {criterion: (docs/PAGE.md#ANCHOR, [what the check's sentence and that section both quote, or
    (the check's words, the page's words)])}: the anchor must be a heading of the page, and the
    error text and line number the check reports must be the ones the page quotes."""
    output = check(student, lab, built=built)
    printed = criteria_printed(output)
    for criterion, (verdict, block) in sorted(printed.items()):
        if verdict == 'PASS':
            assert criterion not in sections, (criterion, block)
            continue
        if criterion not in sections:
            assert re.search(r'seen: not (run|checked): ', block), 'FAIL %s names no section:\n%s' % (criterion, block)
            continue
        named, quotes = sections[criterion]
        links = re.findall(r'\b(docs/[\w/.-]+\.md#[\w-]+)', block)
        assert named in links, '%s: %s not named in:\n%s' % (criterion, named, block)
        text = section(*named.split('#'))
        for quote in quotes:
            in_check, in_page = quote if isinstance(quote, tuple) else (quote, quote)
            assert in_check in block, '%s: the check does not say %r:\n%s' % (criterion, in_check, block)
            assert in_page in text, '%s does not say %r, as the check does' % (named, in_page)
    assert set(sections) <= set(printed), (sorted(sections), sorted(printed))
    return output
