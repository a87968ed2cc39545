"""The teacher's command: grade a class's submissions of a lab, each in its own container (or, with
--no-container, its own process group), in parallel, and write grades.csv, junit/ and report.html."""
import argparse
import os
import pwd
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from concurrent.futures import ThreadPoolExecutor

from course_grader import reports, results, rubric as rubrics
from course_grader.session import PROCESS_GROUPS
from course_grader.submission import SubmissionError, find_package, student_name, unpack
from course_testing import processes

MARKER = '.course_grader'            # in --out: the folder is the grader's (it may empty it)
COURSE_IN_IMAGE = '/home/student/course'
SESSION = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'nodes', 'grade_submission')
MAX_COPIED_BYTES = 50 * 2 ** 20      # of what one sandbox leaves in its output folder
CONTAINER_LIMITS = ['--memory', '1536m', '--memory-swap', '1536m', '--pids-limit', '512',
                    '--cpus', '1', '--ulimit', 'nofile=1024:1024', '--ulimit', 'fsize=104857600',
                    '--tmpfs', '/tmp:rw,exec,nosuid,nodev,size=512m']


class GraderError(Exception):
    """The grader itself cannot run (not a student's problem): one sentence, exit status 2."""


def describe_labs():
    lines = ['labs and their criteria (rubrics in %s):' % os.path.normpath(rubrics.RUBRIC_DIR)]
    for lab in rubrics.labs():
        rubric = rubrics.load(lab)
        lines.append('  %s: %s (%g points)' % (lab, rubric.title, rubric.max_score))
        width = max([18] + [len(c.id) for c in rubric.criteria])
        lines += ['    %-*s %4g  %s' % (width, c.id, c.points, c.title) for c in rubric.criteria]
    return '\n'.join(lines)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='grade.sh', formatter_class=argparse.RawDescriptionHelpFormatter,
        description='Grades every submission of a lab against the course\'s simulators, each in its own '
                    'container, and writes grades.csv, junit/<student>.xml, report.html and a folder per '
                    'student into --out.', epilog=describe_labs())
    parser.add_argument('lab', help='the lab: %s' % ', '.join(rubrics.labs()))
    parser.add_argument('submissions', nargs='+', metavar='SUBMISSION',
                        help='a student\'s folder (the package, or a workspace with src/), .zip or .tar.gz')
    parser.add_argument('--out', default='grades', help='output folder (default: grades/)')
    parser.add_argument('--jobs', type=int, default=2, help='submissions graded at once (default: 2)')
    parser.add_argument('--no-container', action='store_true',
                        help='run on this machine, without isolation (trusted code only)')
    parser.add_argument('--rubric', help='a rubric file of your own (default: rubrics/LAB.yaml)')
    parser.add_argument('--image', default=os.environ.get('COURSE_GRADER_IMAGE'),
                        help='Docker image of the course (grade.sh makes it)')
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error('--jobs must be 1 or more')
    return args


def prepare_out(out):
    """An empty output folder: new, or one the grader wrote before (then its old results go)."""
    if os.path.exists(out) and not os.path.isdir(out):
        raise GraderError('--out %s is a file, not a folder' % out)
    if os.path.isdir(out) and os.listdir(out):
        if not os.path.exists(os.path.join(out, MARKER)):
            raise GraderError('--out %s holds files the grader did not write: give an empty or new folder' % out)
        for name in os.listdir(out):
            path = os.path.join(out, name)
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path)
            else:
                os.remove(path)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, MARKER), 'w') as stream:
        stream.write('written by the course grader; grading again into this folder replaces it all\n')


def copy_output(staging, folder):
    """The regular files the sandbox left (no links, no folders), at most MAX_COPIED_BYTES."""
    copied = 0
    for name in sorted(os.listdir(staging)):
        path = os.path.join(staging, name)
        if name == PROCESS_GROUPS or os.path.islink(path) or not os.path.isfile(path):
            continue
        size = os.path.getsize(path)
        if copied + size > MAX_COPIED_BYTES:
            continue
        shutil.copyfile(path, os.path.join(folder, name), follow_symlinks=False)
        copied += size


def _tail(path, lines=15):
    try:
        with open(path, errors='replace') as stream:
            return '\n'.join(stream.read()[-20000:].splitlines()[-lines:])
    except OSError:
        return ''


def kill_process_groups(listing):
    try:
        with open(listing) as stream:
            groups = {int(line) for line in stream if line.strip().isdigit()}
        os.remove(listing)
    except (OSError, ValueError):
        return
    for group in groups:
        if group > 1 and group != os.getpgid(0):
            try:
                os.killpg(group, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass


def _limit_resources():
    """In the --no-container child: CPU seconds, file size, address space, open files."""
    for limit, value in ((resource.RLIMIT_CPU, 900), (resource.RLIMIT_FSIZE, 100 * 2 ** 20),
                         (resource.RLIMIT_AS, 4 * 2 ** 30), (resource.RLIMIT_NOFILE, 1024)):
        resource.setrlimit(limit, (value, value))


class Grader:
    def __init__(self, args, rubric):
        self.args = args
        self.rubric = rubric
        self.out = os.path.abspath(args.out)
        self.run_id = uuid.uuid4().hex[:8]
        self.lock = threading.Lock()
        self.done = 0
        self.total = 0
        self.started = time.monotonic()
        limits = rubric.limits
        # Build, three runs and the simulators' start-ups: beyond this the sandbox is stopped.
        self.wall_limit = limits['build_seconds'] + 4 * limits['run_seconds'] + 60

    def grade_all(self, submissions):
        self.total = len(submissions)
        with ThreadPoolExecutor(max_workers=self.args.jobs) as pool:
            return list(pool.map(self.grade_one, submissions))

    def grade_one(self, path):
        student = student_name(path)
        started = time.monotonic()
        folder = os.path.join(self.out, student)
        os.makedirs(folder)
        scratch = tempfile.mkdtemp(prefix='course-grader-%s-' % student)
        try:
            result = self._grade(path, student, folder, scratch)
        except Exception as error:   # a fault of the grader for one student: the others go on
            result = results.failed(self.rubric, student, 'the grader failed on this submission: %r' % error)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        result['seconds'] = time.monotonic() - started
        results.write(result, folder)   # the grade as the reports have it (checked against the rubric)
        with self.lock:
            self.done += 1
            print('grade: [%d/%d] %s: %g / %g (%.0f s)%s' % (
                self.done, self.total, student, result['score'], result['max_score'], result['seconds'],
                ': ' + result['error'] if result.get('error') else ''), flush=True)
        return result

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
        os.chmod(staging, 0o777)   # the container's user writes there
        if self.args.no_container:
            reason = self._run_on_host(submission, package, student, staging, scratch)
        else:
            reason = self._run_in_container(submission, package, student, staging)
        copy_output(staging, folder)
        result = results.read(self.rubric, student, folder)
        if result is None:
            return results.failed(self.rubric, student, reason or 'the grading stopped without a result '
                                  '(see grader.txt)')
        return result

    def _session_args(self, package, out, scratch, student):
        args = ['--lab', self.rubric.lab, '--package', package, '--out', out, '--scratch', scratch,
                '--student', student]
        return args

    def _run_in_container(self, submission, package, student, staging):
        name = 'course-grader-%s-%s' % (self.run_id, student)
        rubric_mount = []
        rubric = '%s/src/course_grader/rubrics/%s.yaml' % (COURSE_IN_IMAGE, self.rubric.lab)
        if self.args.rubric:
            rubric_mount = ['-v', '%s:/rubric.yaml:ro' % os.path.abspath(self.args.rubric)]
            rubric = '/rubric.yaml'
        # --init: a reaper as PID 1, so that what the submission forks and leaves behind is reaped.
        # --rm as well as the rm -f below: the engine removes it even if this process is killed.
        command = ['docker', 'run', '--rm', '--name', name, '--init', '--network', 'none', '--user', 'student',
                   '--read-only', '--security-opt', 'no-new-privileges', '--cap-drop', 'ALL',
                   '-e', 'ROS_HOME=/tmp/ros', '-e', 'HOME=/tmp/home',
                   '-v', '%s:/submission:ro' % submission, '-v', '%s:/out' % staging] + rubric_mount \
            + CONTAINER_LIMITS + [self.args.image, 'bash', '-c',
                                  'mkdir -p /tmp/home /tmp/ws && source tools/env.sh && exec rosrun course_grader '
                                  'grade_submission "$@"', 'grade_submission', '--rubric', rubric] \
            + self._session_args('/submission/' + package, '/out', '/tmp/ws', student)
        log = os.path.join(staging, 'grader.txt')
        try:
            with open(log, 'wb') as stream:
                process = subprocess.Popen(command, stdout=stream, stderr=subprocess.STDOUT)
                try:
                    code = process.wait(self.wall_limit)
                except subprocess.TimeoutExpired:
                    code = None
        finally:
            # Whatever happened: the container and everything in it are gone.
            subprocess.run(['docker', 'rm', '-f', name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            if 'process' in locals() and process.poll() is None:
                process.kill()
                process.wait()
        return self._reason(code, log)

    def _run_on_host(self, submission, package, student, staging, scratch):
        from course_testing.processes import stop_process_group
        work = os.path.join(scratch, 'ws')
        os.makedirs(work)
        env = dict(os.environ, ROS_HOME=os.path.join(scratch, 'ros'))
        argv = ['/usr/bin/python3', os.path.normpath(SESSION)]
        if self.args.rubric:
            argv += ['--rubric', os.path.abspath(self.args.rubric)]
        argv += self._session_args(os.path.join(submission, package), staging, work, student)
        log = os.path.join(staging, 'grader.txt')
        with open(log, 'wb') as stream:
            process = subprocess.Popen(argv, stdout=stream, stderr=subprocess.STDOUT, env=env,
                                       start_new_session=True, preexec_fn=_limit_resources)
            try:
                code = process.wait(self.wall_limit)
            except subprocess.TimeoutExpired:
                code = None
            finally:
                stop_process_group(process, 10)
                # The session started roscore, the simulators and the student's nodes in process
                # groups of their own, and stops them; if it could not, they go now.
                kill_process_groups(os.path.join(staging, PROCESS_GROUPS))
        return self._reason(code, log)

    def _reason(self, code, log):
        if code is None:
            return 'the grading did not end within %d s and was stopped' % self.wall_limit
        if code == 137:
            return 'the sandbox was killed (out of memory, %s): %s' % (CONTAINER_LIMITS[1], _tail(log, 3))
        if code != 0:
            return 'the grading stopped with exit status %d: %s' % (code, _tail(log, 5))
        return None


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
        names = [student_name(path) for path in args.submissions]
        twice = sorted({name for name in names if names.count(name) > 1})
        if twice:
            raise GraderError('two submissions have the same student name: %s' % ', '.join(twice))
        if args.no_container:
            print('grade: --no-container: NOTHING IS ISOLATED: the students\' code runs on this machine as '
                  'user %s, with only time and resource limits. Grade this way only code you trust.'
                  % pwd.getpwuid(os.getuid()).pw_name, flush=True)
        elif not args.image:
            raise GraderError('no Docker image given (--image, or run ./grade.sh which makes it)')
        prepare_out(args.out)
    except (rubrics.RubricError, GraderError, OSError) as error:
        print('grade: %s' % error, file=sys.stderr)
        return 2
    print('grade: %d submissions of %s, %d at a time%s' % (
        len(args.submissions), args.lab, args.jobs, '' if args.no_container else ', each in a container of '
        + args.image), flush=True)
    grader = Grader(args, rubric)
    class_results = grader.grade_all(args.submissions)
    seconds = time.monotonic() - started
    reports.write_all(class_results, rubric, grader.out, seconds)
    print('grade: %d students graded in %.0f s (%.1f s per student): %s, %s, %s' % (
        len(class_results), seconds, seconds / len(class_results), os.path.join(args.out, 'grades.csv'),
        os.path.join(args.out, 'report.html'), os.path.join(args.out, 'junit/')), flush=True)
    return 0
