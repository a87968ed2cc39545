"""The student's command: `rosrun course_grader check LAB [PACKAGE_PATH] [--only ID]` grades the
student's own package with the lab's rubric on this machine (the teacher's grading with
--no-container, same rubric, same verdicts) and prints each criterion in the terminal. What it
showed, its pictures and its runs stay in ROS_HOME/course_check/LAB/ (course_web.last_check) for the
browser view's "Your last check"."""
import argparse
import datetime
import importlib
import json
import os
import shutil
import sys
import threading
import time
import urllib.request

from course_grader import results, rubric as rubrics
from course_grader.grader import Grader
from course_grader.sandbox import Options
from course_grader.submission import package_name, terminal_text
from course_common.processes import exit_on_terminate
from course_web import last_check

BUILD_CACHE = '.build'   # in ROS_HOME/course_check: each lab's kept build (not a check: never pruned)
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


def summary(result, lab, package, runs, last_line, only=None, due=None, now=None):
    """What check.json holds for the browser view (course_web.last_check): what print_result shows,
    a hidden criterion as its title and why it is hidden, the pictures, the runs (replay_runs)."""
    when = (now or datetime.datetime.now(datetime.timezone.utc)).astimezone()
    criteria = []
    for criterion in result['criteria']:
        if only and criterion['id'] != only:
            continue
        shown = {key: criterion[key] for key in ('id', 'title')}
        if results.shown_to_student(criterion, due, now):
            shown.update({key: criterion[key] for key in ('passed', 'points', 'max_points', 'reason', 'hints')})
        else:
            shown['hidden'] = results.HIDDEN[criterion['visibility']]
        criteria.append(shown)
    return {'lab': lab, 'package': package, 'folder': result['folder'], 'criteria': criteria,
            'total': last_line, 'error': result.get('error'), 'notes': result.get('notes', []),
            'pictures': result.get('pictures', []), 'runs': runs, 'counts': COUNTS,
            'when': when.strftime('%Y-%m-%d %H:%M:%S')}


def replay_runs(student):
    """Each run's rosbag in the student's folder made into RUN.replay.js for the browser's player:
    [{run}], or {run, error} for one that cannot be played back."""
    from course_grader import replay
    from course_grader.bags import BAG_SUFFIX
    runs = []
    for name in sorted(name for name in os.listdir(student) if name.endswith(BAG_SUFFIX)):
        run = {'run': name[:-len(BAG_SUFFIX)]}
        try:
            replay.write_replay(os.path.join(student, name))
        except replay.ReplayError as error:
            run['error'] = str(error)
        runs.append(run)
    return runs


def view_shows(address, check):
    """Whether the browser view answers at address and shows this check (LAB/STAMP) as the last one."""
    direct = urllib.request.build_opener(urllib.request.ProxyHandler({}))   # never through an http_proxy
    try:
        with direct.open(address + 'check/latest', timeout=2) as answer:
            return json.load(answer).get('check') == check
    except (OSError, ValueError, AttributeError):
        return False


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
        checks = last_check.default_root()
        try:
            out = last_check.new_check_folder(checks, args.lab)
        except OSError as error:
            raise CheckError('cannot make a folder for the check in %s (%s): set ROS_HOME to a folder '
                             'of yours' % (checks, error.strerror or error)) from None
    except (CheckError, rubrics.RubricError) as error:
        print('check: %s' % error, file=sys.stderr)
        return 2
    # Closing the terminal or `kill` stops the check as Ctrl-C does: with all it started.
    exit_on_terminate()
    # rosbag, which the replays need (a third of a second), imported while the session runs.
    threading.Thread(target=importlib.import_module, args=('course_grader.replay',), daemon=True).start()
    print('check: grading the package at %s with the rubric of %s, on this machine%s'
          % (folder, args.lab, ', the criterion %s only' % args.only if args.only else ''), flush=True)
    # The build of the last check of this lab kept (grading_session.BuildCache): catkin_make builds
    # only what changed, as the student's own does; on all the machine's cores (one session).
    options = Options(only=args.only, on_step=lambda step: print('check: %s' % step, flush=True),
                      build_cache=os.path.join(checks, BUILD_CACHE, args.lab), build_jobs=os.cpu_count() or 1)
    try:
        result = Grader(rubric, out, options, announce=False).grade_one(folder)
    except KeyboardInterrupt:   # what it started is stopped by then (the session's finally blocks)
        shutil.rmtree(out, ignore_errors=True)   # no half check among the kept ones
        print('check: stopped (Ctrl-C) before the end: nothing was checked, your last check is still '
              'the one shown', file=sys.stderr, flush=True)
        return 130
    due = rubric.late.due() if rubric.late else None
    print_result(result, args.only, due)
    student = os.path.join(out, result['folder'])
    runs = replay_runs(student)
    seconds = time.monotonic() - started
    if args.only:
        criterion = next(c for c in result['criteria'] if c['id'] == args.only)
        last_line = '%s %s, the other criteria not checked (%.0f s)' % (
            args.only, '%g / %g' % (criterion['points'], criterion['max_points'])
            if results.shown_to_student(criterion, due) else results.HIDDEN[criterion['visibility']], seconds)
    else:
        last_line = 'total %s (%.0f s)' % (total_text(result, due), seconds)
    last_check.write_summary(out, summary(result, args.lab, folder, runs, last_line, args.only, due))
    last_check.point_latest(checks, out)
    last_check.prune(checks, args.lab)
    print('check: pictures and logs in %s (the last %d checks of each lab are kept)'
          % (student, last_check.KEEP_PER_LAB))
    for run in runs:
        if run.get('error'):
            print('check: the run %s cannot be replayed: %s' % (run['run'], run['error']))
    address = 'http://localhost:%s/' % os.environ.get('COURSE_WEB_PORT', '8080')
    if view_shows(address, os.path.relpath(out, checks)):
        print('check: open %s (Your last check): this result, its pictures and each run played again' % address)
    else:
        print('check: to see this result, its pictures and each run played again in a browser: '
              'roslaunch course_web view.launch, then open %s (Your last check)' % address)
    for note in result.get('notes', []):
        print('check: note: %s' % terminal_text(note, keep_lines=True))
    print('check: %s' % last_line)
    print('check: %s' % COUNTS)
    return 0
