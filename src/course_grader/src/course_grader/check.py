"""The student's command: `rosrun course_grader check LAB [PACKAGE_PATH] [--only ID]` grades the
student's own package with the lab's rubric on this machine (the teacher's grading with
--no-container, same rubric, same verdicts) and prints each criterion in the terminal."""
import argparse
import os
import sys
import tempfile
import time

from course_grader import results, rubric as rubrics
from course_grader.grader import Grader
from course_grader.sandbox import Options
from course_grader.submission import package_name, terminal_text
from course_common.processes import exit_on_terminate

COUNTS = ('This is your own check: the teacher\'s run, in a container, is the one that counts.')


class CheckError(Exception):
    """The check cannot run at all: one sentence, exit status 2."""


def _rospack_path(name):
    import rospkg
    try:
        return rospkg.RosPack().get_path(name)
    except rospkg.ResourceNotFound:
        return None


def project_src():
    """The source folder of the project's own packages (where its reference labs live)."""
    here = _rospack_path('course_grader')
    return os.path.dirname(os.path.realpath(here)) if here else None


def find_student_package(lab, path):
    """The folder of the student's package: the given path, or the sourced overlay's LAB."""
    if path:
        folder = os.path.abspath(path)
        if not os.path.isfile(os.path.join(folder, 'package.xml')):
            raise CheckError('%s is not a package: it has no package.xml (give the folder made by '
                             'catkin_create_pkg %s)' % (path, lab))
        name = package_name(os.path.join(folder, 'package.xml'))
        if name != lab:
            raise CheckError('%s is the package %s, not %s: the lab %s grades a package named %s'
                             % (path, name, lab, lab, lab))
        return folder
    found = _rospack_path(lab)
    reference = project_src()
    if found is None or (reference and os.path.dirname(os.path.realpath(found)) == reference):
        raise CheckError('no package %s of your own was found (%s): source your workspace first '
                         '(source ~/catkin_ws/devel/setup.bash, see docs/student-workspace.md), or give '
                         'its path: rosrun course_grader check %s ~/catkin_ws/src/%s'
                         % (lab, 'rospack finds only the course\'s own reference package at %s' % found
                            if found else 'rospack finds none', lab, lab))
    return found


def print_result(result, only=None, due=None, everything=False, now=None):
    """Each criterion the student may see (results.shown_to_student: `due` is when after_due_date
    ones are shown) with its points, reason and hints; the others as one line saying they are
    hidden. With everything, all of them in full (the teacher's log)."""
    for criterion in result['criteria']:
        if only and criterion['id'] != only:
            continue
        if not (everything or results.shown_to_student(criterion, due, now)):
            print('---- %-22s %s: %s' % (criterion['id'], criterion['title'], results.HIDDEN[criterion['visibility']]))
            continue
        print('%s %-22s %g / %g  %s' % ('PASS' if criterion['passed'] else 'FAIL', criterion['id'],
                                        criterion['points'], criterion['max_points'], criterion['title']))
        if criterion['reason']:
            print('    seen: %s' % terminal_text(criterion['reason'], keep_lines=True))
        for hint in criterion['hints']:
            print('    hint: %s' % terminal_text(hint, keep_lines=True))
    if result.get('error'):
        print('check: %s' % terminal_text(result['error'], keep_lines=True))


def total_text(result, due=None, everything=False, now=None):
    """'10 / 12, 1 criterion hidden (not counted)': the total over what print_result showed."""
    if everything:
        return '%g / %g' % (result['score'], result['max_score'])
    points, maximum, hidden = results.shown_total(result, due, now)
    hidden_text = ', %d criteri%s hidden (not counted)' % (hidden, 'on' if hidden == 1 else 'a') if hidden else ''
    return '%g / %g%s' % (points, maximum, hidden_text)


def main(argv=None):
    parser = argparse.ArgumentParser(prog='rosrun course_grader check', description=__doc__)
    parser.add_argument('lab', help='the lab: %s' % ', '.join(rubrics.labs()))
    parser.add_argument('package_path', nargs='?', help='your package (default: rospack find LAB)')
    parser.add_argument('--only', metavar='ID', help='check one criterion')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    started = time.monotonic()
    try:
        if args.lab not in rubrics.labs():
            raise CheckError('there is no lab %s; the labs are %s' % (args.lab, ', '.join(rubrics.labs())))
        rubric = rubrics.load(args.lab)
        known = [c.id for c in rubric.criteria]
        if args.only and args.only not in known:
            raise CheckError('%s has no criterion %s; its criteria are %s' % (args.lab, args.only, ', '.join(known)))
        folder = find_student_package(args.lab, args.package_path)
    except (CheckError, rubrics.RubricError) as error:
        print('check: %s' % error, file=sys.stderr)
        return 2
    # Closing the terminal or `kill` stops the check as Ctrl-C does: with all it started.
    exit_on_terminate()
    out = tempfile.mkdtemp(prefix='course-check-%s-' % args.lab)
    print('check: grading the package at %s with the rubric of %s, on this machine%s'
          % (folder, args.lab, ', the criterion %s only' % args.only if args.only else ''), flush=True)
    options = Options(only=args.only, on_step=lambda step: print('check: %s' % step, flush=True))
    result = Grader(rubric, out, options, announce=False).grade_one(folder)
    due = rubric.late.due() if rubric.late else None
    print_result(result, args.only, due)
    student = os.path.join(out, result['folder'])
    print('check: pictures and logs in %s' % student)
    kept = sorted(name for name in os.listdir(student) if name.endswith('.bag'))
    if kept:
        print('check: each run as a rosbag in %s; to play one in the browser (http://localhost:8080/):' % student)
        for name in kept:
            print('    roslaunch course_web replay.launch bag:=%s' % os.path.join(student, name))
    for note in result.get('notes', []):
        print('check: note: %s' % terminal_text(note, keep_lines=True))
    seconds = time.monotonic() - started
    if args.only:
        criterion = next(c for c in result['criteria'] if c['id'] == args.only)
        print('check: %s %s, the other criteria not checked (%.0f s)' % (
            args.only, '%g / %g' % (criterion['points'], criterion['max_points'])
            if results.shown_to_student(criterion, due) else results.HIDDEN[criterion['visibility']], seconds))
    else:
        print('check: total %s (%.0f s)' % (total_text(result, due), seconds))
    print('check: %s' % COUNTS)
    return 0
