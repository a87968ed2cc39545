"""One submission graded where a platform put it, by a process that is the trusted side of the
course's image (`rosrun course_grader grade_platform --help`): GitHub Classroom's grading step (a
container started as ./grade.sh starts one) and Gradescope's run_autograder (its own container).

The grading is ./grade.sh's: grade_submission as root, the student's side as the user `student`,
the rubric's time limits and the grader's wall limit, the result read back against the rubric;
only the platform's file differs (classroom.py, gradescope.py)."""
import argparse
import contextlib
import os
import shutil
import sys
import tempfile
import time
import uuid

from course_grader import classroom, feedback, gradescope, results, rubric as rubrics, sandbox
from course_grader.check import print_result, total_text
from course_grader.submission import (MAX_UNPACKED_BYTES, SubmissionError, check_folder, find_package, terminal_text,
                                      unpack, upload_inside)


def is_empty(folder):
    """True when the submission holds nothing but hidden entries (.git, .github)."""
    return not [name for name in os.listdir(folder) if not name.startswith('.')]


def stage(folder, rubric, staging):
    """The submission in `staging` (an empty folder), readable by the student's side: a copy of
    `folder`, or, when it holds one archive and no package.xml (an uploaded .zip), the archive
    unpacked (submission.upload_inside). Returns the package's folder relative to staging, or raises a SubmissionError that
    says in one sentence why there is none to grade."""
    if not os.path.isdir(folder):
        raise SubmissionError('no submission at %s' % folder)
    if is_empty(folder):
        raise SubmissionError('the submission is empty: hand in the package %s (the folder made by '
                              'catkin_create_pkg %s), at the top or in src/' % (rubric.package, rubric.package))
    check_folder(folder)
    upload = upload_inside(folder)   # the one archive uploaded, as ./grade.sh takes it
    if upload:
        unpack(upload, staging)
    else:
        size = 0
        for parent, dirs, files in os.walk(folder):
            dirs[:] = [d for d in dirs if d != '.git']   # the repository's history is not graded
            size += sum(os.path.getsize(os.path.join(parent, name)) for name in files
                        if not os.path.islink(os.path.join(parent, name)))
        if size > MAX_UNPACKED_BYTES:
            raise SubmissionError('the submission holds more than %d MB: refused' % (MAX_UNPACKED_BYTES // 2 ** 20))
        shutil.rmtree(staging)
        shutil.copytree(folder, staging, symlinks=True, ignore=shutil.ignore_patterns('.git'))
    for parent, dirs, files in os.walk(staging):
        for name in dirs + files:
            path = os.path.join(parent, name)
            if not os.path.islink(path):
                os.chmod(path, 0o755 if os.path.isdir(path) or os.stat(path).st_mode & 0o111 else 0o644)
    os.chmod(staging, 0o755)
    return find_package(staging, rubric.package)


def grade_folder(rubric, folder, student, work, student_user='student'):
    """The result (results.score's dict) of the submission in `folder`. `work` is the trusted
    side's own folder (its logs and the result; nothing of the student's side can write there)."""
    started = time.monotonic()
    submission = tempfile.mkdtemp(prefix='course-submission-')
    staging = tempfile.mkdtemp(prefix='course-result-', dir=work)
    try:
        package = stage(folder, rubric, submission)
        grading = sandbox.Grading(rubric, submission, package, student, staging)
        reason = sandbox.in_place(grading, sandbox.Options(), work, student_user)
        result = results.read(rubric, student, staging) or results.failed(
            rubric, student, reason or 'the grading stopped without a result: %s'
            % feedback.log_tail(os.path.join(staging, 'grader.txt'), 5))
    except SubmissionError as error:
        result = results.failed(rubric, student, str(error))
    finally:
        for path in (staging, submission):
            shutil.rmtree(path, ignore_errors=True)
    result['seconds'] = time.monotonic() - started
    return result


def deliver_gradescope(result, folder, fd, work):
    """Gradescope's results.json of `result`: its text on the descriptor `fd` when given
    (run_autograder opens it outside the chroot the grading runs in, on a file nothing inside can
    reach), else into `folder`, renamed over whatever is there: a link planted at that name (by an
    unpacking, which runs as root) is replaced, never written through."""
    if fd is None:
        os.makedirs(folder, exist_ok=True)
        private = tempfile.mkdtemp(prefix='.results-', dir=folder)   # the same disk: the rename is atomic
        gradescope.write(result, private)
        os.replace(os.path.join(private, gradescope.RESULTS_FILE), os.path.join(folder, gradescope.RESULTS_FILE))
        os.rmdir(private)
        return
    private = tempfile.mkdtemp(prefix='results-', dir=work)
    gradescope.write(result, private)
    with open(os.path.join(private, gradescope.RESULTS_FILE), 'rb') as source, os.fdopen(fd, 'wb') as target:
        shutil.copyfileobj(source, target)
    shutil.rmtree(private)


def report(result, stream, runner_log=False, due=None, everything=False):
    """Each criterion, its points, reason and hints, then the total, as `check` prints them: a
    criterion the student may not see yet as one line (`due`: when after_due_date ones are shown),
    unless everything (Gradescope's log, which only the teacher reads). In a runner's log (which the
    student reads), between ::stop-commands:: and its token, so that nothing a reason quotes of the
    student's output is taken for a workflow command."""
    token = uuid.uuid4().hex
    with contextlib.redirect_stdout(stream):
        if runner_log:
            print('::stop-commands::%s' % token)
        print('%s: %s' % (result['lab'], terminal_text(result['student'])))
        error = result.get('error')
        if not (error and all(c['reason'] == error for c in result['criteria'])):   # else nothing was graded
            print_result(dict(result, error=None), due=due, everything=everything)
        if error:
            print('not fully graded: %s' % terminal_text(error, keep_lines=True))
        print('total %s (%.0f s)' % (total_text(result, due, everything), result['seconds'] or 0))
        if runner_log:
            print('::%s::' % token)
    stream.flush()


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog='rosrun course_grader grade_platform', description='Grades the submission in FOLDER for a '
        'platform, as the trusted side of the course\'s image (run as root): classroom prints the outputs '
        'of the workflow\'s grading step on standard output (the report on standard error); gradescope '
        'writes RESULTS/results.json, or its text on the descriptor FD (the report on standard output).')
    parser.add_argument('platform', choices=('classroom', 'gradescope'))
    parser.add_argument('lab', help='the lab: %s' % ', '.join(rubrics.labs()))
    parser.add_argument('folder', help='the submission (the repository, or what the student uploaded)')
    parser.add_argument('--results', default='/autograder/results', help='gradescope: where results.json goes')
    parser.add_argument('--results-fd', type=int, metavar='FD',
                        help='gradescope: write results.json\'s text on this open descriptor instead of RESULTS')
    parser.add_argument('--student', default='submission', help='the name in the report')
    parser.add_argument('--work', help='the trusted side\'s folder (default: a new one in the temporary folder)')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    # Standard output carries the outputs only: whatever else is printed goes to standard error.
    result_stream = os.fdopen(os.dup(1), 'w') if args.platform == 'classroom' else sys.stdout
    if args.platform == 'classroom':
        os.dup2(2, 1)
    try:
        rubric = rubrics.load(args.lab)
    except rubrics.RubricError as error:
        print('grade_platform: %s' % error, file=sys.stderr)
        return 2
    work = args.work or tempfile.mkdtemp(prefix='course-grader-')
    os.makedirs(work, mode=0o700, exist_ok=True)
    try:
        result = grade_folder(rubric, args.folder, args.student, work)
    except Exception as error:   # a fault of the grader: the platform still gets a result saying so
        result = results.failed(rubric, args.student, 'the grader failed on this submission: %r' % error, seconds=0)
    due = rubric.late.due() if rubric.late else None   # shows after_due_date criteria; no late penalty here
    if args.platform == 'classroom':
        report(result, sys.stderr, runner_log=True, due=due)
        result_stream.write(classroom.output_lines(result, due))
        result_stream.close()
    else:
        deliver_gradescope(result, args.results, args.results_fd, work)
        report(result, sys.stdout, everything=True)
    return 0
