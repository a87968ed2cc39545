"""The teacher's command: grade a class's submissions of a lab, each in its own container (or, with
--no-container, its own process group), in parallel, and write grades.csv, junit/ and report.html."""
import argparse
import os
import pwd
import shutil
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor

from course_common import processes
from course_grader import gradescope, results, rubric as rubrics, sandbox
from course_grader.submission import (SubmissionError, ascii_name, find_package, student_of, submitted, terminal_text,
                                      unpack)

MARKER = '.course_grader'            # in --out: the folder is the grader's (it may empty it)


class GraderError(Exception):
    """The grader itself cannot run (not a student's problem): one sentence, exit status 2."""


def describe_labs():
    lines = ['labs and their criteria (rubrics in %s):' % rubrics.rubric_dir()]
    for lab in rubrics.labs():
        rubric = rubrics.load(lab)
        lines.append('  %s: %s (%g points)' % (lab, rubric.title, rubric.max_score))
        width = max([18] + [len(c.id) for c in rubric.criteria])
        lines += ['    %-*s %4g  %s' % (width, c.id, c.points, c.title) for c in rubric.criteria]
    return '\n'.join(lines)


def _deadline(text):
    try:
        return rubrics.parse_deadline(text, '--deadline')
    except rubrics.RubricError as error:
        raise argparse.ArgumentTypeError(str(error))


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='grade.sh', formatter_class=argparse.RawDescriptionHelpFormatter,
        description='Grades every submission of a lab against the course\'s simulators, each in its own '
                    'container, and writes grades.csv, junit/<student>.xml, report.html and a folder per '
                    'student into --out.', epilog=describe_labs())
    parser.add_argument('lab', help='the lab: %s' % ', '.join(rubrics.labs()))
    parser.add_argument('submissions', nargs='+', metavar='SUBMISSION',
                        help='a student\'s folder (the package, or a workspace with src/), .zip or .tar.gz, '
                             'or a learning platform\'s folder or file of one student (docs/grading.md)')
    parser.add_argument('--out', default='grades', help='output folder (default: grades/)')
    parser.add_argument('--jobs', type=int, default=2, help='submissions graded at once (default: 2)')
    parser.add_argument('--no-container', action='store_true',
                        help='run on this machine, without isolation (trusted code only)')
    parser.add_argument('--rubric', help='a rubric file of your own (default: rubrics/LAB.yaml)')
    parser.add_argument('--deadline', type=_deadline, metavar='TIME',
                        help='the deadline, ISO 8601 with its timezone (2026-12-01T23:59+01:00): work handed in '
                             'later loses the rubric\'s late.per_day (default: the rubric\'s late.deadline)')
    parser.add_argument('--image', default=os.environ.get('COURSE_GRADER_IMAGE'),
                        help='Docker image of the course (grade.sh makes it)')
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error('--jobs must be 1 or more')
    return args


def prepare_out(out):
    """An empty output folder: new, or one the grader wrote before (then its old results go).
    Returns the results of that earlier grading by student folder ({} for a new folder)."""
    if os.path.exists(out) and not os.path.isdir(out):
        raise GraderError('--out %s is a file, not a folder' % out)
    previous = {}
    if os.path.isdir(out) and os.listdir(out):
        if not os.path.exists(os.path.join(out, MARKER)):
            raise GraderError('--out %s holds files the grader did not write: give an empty or new folder' % out)
        previous = results.read_earlier(out)
        if not os.access(out, os.W_OK):
            raise GraderError('--out %s cannot be written (permission denied): nothing was graded' % out)
        for name in os.listdir(out):
            path = os.path.join(out, name)
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path)
            else:
                os.remove(path)
    try:
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, MARKER), 'w') as stream:
            stream.write('written by the course grader; grading again into this folder replaces it all\n')
    except OSError as error:
        raise GraderError('--out %s cannot be written (%s): nothing was graded' % (out, error.strerror or error))
    return previous


class Grader:
    """The submissions of one lab graded, `jobs` at a time, each in its sandbox (sandbox.Options),
    each student's folder, result and Gradescope file written into `out`."""

    def __init__(self, rubric, out, options, jobs=1, announce=True):
        self.rubric = rubric
        self.out = os.path.abspath(out)
        self.options = options
        self.jobs = jobs
        self.announce = announce   # a line per graded student ("grade: [3/30] ...")
        self.previous = {}         # folder name: the result of the last grading into the same --out
        self.late = None           # the late policy (rubric.LatePolicy with a deadline), or None
        self.lock = threading.Lock()
        self.done = 0
        self.total = 0
        self.interrupted = threading.Event()   # Ctrl-C: the gradings under way are cut short

    def grade_all(self, submissions):
        """Every submission's result, in order. On Ctrl-C (KeyboardInterrupt here) the ones not
        started never start, the ones under way end (their sessions got the Ctrl-C too) with no
        grade, folder nor line, and the KeyboardInterrupt goes on: a grading cut short is no 0."""
        self.total = len(submissions)
        pool = ThreadPoolExecutor(max_workers=self.jobs)
        try:
            return list(pool.map(self.grade_one, submissions))
        except KeyboardInterrupt:
            self.interrupted.set()
            raise
        finally:
            pool.shutdown(wait=True, cancel_futures=True)

    def grade_one(self, path):
        who = student_of(path)
        student = who.folder   # the student's folder in --out, and the name the sandbox is given
        started = time.monotonic()
        folder = os.path.join(self.out, student)
        os.makedirs(folder)
        scratch = tempfile.mkdtemp(prefix='course-grader-%s-' % ascii_name(student))
        try:
            result = self._grade(path, student, folder, scratch)
        except Exception as error:   # a fault of the grader for one student: the others go on
            result = results.failed(self.rubric, student, 'the grader failed on this submission: %r' % error)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        if self.interrupted.is_set():
            shutil.rmtree(folder, ignore_errors=True)
            return None
        result.update(seconds=time.monotonic() - started, student=who.name, student_id=who.id, folder=student)
        if self.late:
            result = results.with_late(result, self.late, submitted(path))
        results.write(result, folder)   # the grade as the reports have it (checked against the rubric)
        gradescope.write(result, folder)
        with self.lock:
            self.done += 1
            if not self.announce:
                return result
            print('grade: [%d/%d] %s: %g / %g (%.0f s)%s%s%s' % (
                self.done, self.total, terminal_text(who.name + (' (%s)' % who.id if who.id else '')),
                result['score'], result['max_score'], result['seconds'],
                ': ' + terminal_text(result['error']) if result.get('error') else '',
                '; ' + terminal_text(results.describe_late(result['late'])) if result.get('late') else '',
                self._since_last(student, result)), flush=True)
        return result

    def _since_last(self, student, result):
        """What changed since the last grading into --out, for the student's line ('' the first time)."""
        if self.previous and student not in self.previous:
            return '; not in the last grading'
        return results.describe_change(results.change(self.previous.get(student), result))

    def _grade(self, path, student, folder, scratch):
        unpacked = os.path.join(scratch, 'submission')
        os.makedirs(unpacked)
        try:
            submission = unpack(path, unpacked)
            package = find_package(submission, self.rubric.package)
        except SubmissionError as error:
            return results.failed(self.rubric, student, str(error))
        staging = os.path.join(scratch, 'out')
        os.makedirs(staging)
        reason = sandbox.run(sandbox.Grading(self.rubric, submission, package, student, staging), self.options)
        sandbox.copy_output(staging, folder)
        result = results.read(self.rubric, student, folder)
        if result is None:
            return results.failed(self.rubric, student, reason or 'the grading stopped without a result '
                                  '(see grader.txt)')
        return result


def main(argv=None):
    started = time.monotonic()
    processes.restore_ctrl_c()  # grading must not depend on how the teacher started ./grade.sh
    try:
        args = parse_args(sys.argv[1:] if argv is None else argv)
        rubric = rubrics.load(args.rubric or args.lab)
        if rubric.lab != args.lab:
            raise GraderError('the rubric %s is for lab %s, not %s' % (args.rubric, rubric.lab, args.lab))
        missing = [path for path in args.submissions if not os.path.exists(path)]
        if missing:
            raise GraderError('no such submission: %s' % ', '.join(missing))
        names = [student_of(path).folder for path in args.submissions]
        twice = sorted({name for name in names if names.count(name) > 1})
        if twice:
            raise GraderError('two submissions have the same student name: %s' % ', '.join(twice))
        if args.no_container:
            print('grade: --no-container: NOTHING IS ISOLATED: the students\' code runs on this machine as '
                  'user %s, with only time and resource limits. Grade this way only code you trust.'
                  % pwd.getpwuid(os.getuid()).pw_name, flush=True)
        elif not args.image:
            raise GraderError('no Docker image given (--image, or run ./grade.sh which makes it)')
        if args.deadline and not rubric.late:
            raise GraderError('--deadline needs the rubric\'s late policy (late: with %s): %s has none'
                              % (', '.join(rubrics.LATE_KEYS), rubric.path))
        late = rubric.late.with_deadline(args.deadline) if args.deadline else rubric.late
        previous = prepare_out(args.out)
    except (rubrics.RubricError, GraderError, OSError) as error:
        print('grade: %s' % terminal_text(error), file=sys.stderr)
        return 2
    print('grade: %d submissions of %s, %d at a time%s' % (
        len(args.submissions), args.lab, args.jobs, '' if args.no_container else ', each in a container of '
        + args.image), flush=True)
    options = sandbox.Options(image=None if args.no_container else args.image, rubric_file=args.rubric)
    grader = Grader(rubric, args.out, options, args.jobs)
    grader.previous = previous
    if late and late.deadline:
        grader.late = late
        print('grade: late work: after %s%s, -%g%% of the maximum score per day begun, at most -%g%%' % (
            late.deadline.isoformat(), ' and %g minutes of grace' % (late.grace.total_seconds() / 60)
            if late.grace else '', late.per_day, late.cap), flush=True)
    try:
        class_results = grader.grade_all(args.submissions)
    except KeyboardInterrupt:
        print('grade: interrupted (Ctrl-C) after %d of %d students: %s holds their results, but no '
              'grades.csv nor report; grade again to grade the class' % (grader.done, len(args.submissions),
                                                                         args.out), file=sys.stderr, flush=True)
        return 130
    seconds = time.monotonic() - started
    gone = sorted(set(previous) - {result['folder'] for result in class_results})
    if gone:
        print('grade: graded last time into %s, not this time: %s' % (args.out, ', '.join(
            '%s (%g / %g)' % (terminal_text(previous[f]['student']), previous[f]['score'], previous[f]['max_score'])
            for f in gone)))
    # The class's reports here only: the student's check (Grader alone) does without their imports (rosbag).
    from course_grader import reports, similarity
    print('grade: %s' % similarity.write_class(args.lab, rubric.package, args.submissions, grader.out,
                                               options.image), flush=True)
    reports.write_all(class_results, rubric, grader.out, seconds, previous)
    print('grade: %d students graded in %.0f s (%.1f s per student): %s, %s, %s' % (
        len(class_results), seconds, seconds / len(class_results), os.path.join(args.out, 'grades.csv'),
        os.path.join(args.out, 'report.html'), os.path.join(args.out, 'junit/')), flush=True)
    return 0
