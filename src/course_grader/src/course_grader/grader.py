"""The teacher's command: grade a class's submissions of a lab, each in its own container (or, with
--no-container, its own process group), in parallel, and write grades.csv, junit/ and report.html."""
import argparse
import io
import os
import pwd
import resource
import shutil
import subprocess
import sys
import tarfile
import tempfile
import threading
import time
import uuid
from concurrent.futures import ThreadPoolExecutor

from course_grader import feedback, gradescope, reports, results, rubric as rubrics, wall_limit
from course_grader.submission import SubmissionError, ascii_name, find_package, student_of, terminal_text, unpack
from course_common import processes
from course_common.process_table import stop_marked
from course_common.waiting import poll_until

MARKER = '.course_grader'            # in --out: the folder is the grader's (it may empty it)
RUN_MARK = 'COURSE_GRADER_RUN'       # in the environment of everything a --no-container session starts
MAX_COPIED_BYTES = 50 * 2 ** 20      # of what one sandbox leaves in its output folder
# The grading session (grade_submission), by its module: rosrun's look-up costs half a second.
SESSION = ['/usr/bin/python3', '-m', 'course_grader.grading_session']
STEP_PREFIX = 'grade_submission: '   # a line of the session that reports a step and its time
# The trusted side of a container is root with no capability but these: start the student's side
# as the user `student`, and stop it. No write access anywhere else, no other user's processes.
TRUSTED_CAPABILITIES = ['--cap-drop', 'ALL', '--cap-add', 'SETUID', '--cap-add', 'SETGID', '--cap-add', 'KILL']
CONTAINER_LIMITS = ['--memory', '1536m', '--memory-swap', '1536m', '--pids-limit', '512',
                    '--cpus', '1', '--ulimit', 'nofile=1024:1024', '--ulimit', 'fsize=104857600',
                    '--tmpfs', '/tmp:rw,exec,nosuid,nodev,size=512m',
                    # The trusted side's own disk: a submission that fills /tmp cannot stop its logs.
                    '--tmpfs', '/grader:rw,noexec,nosuid,nodev,size=128m,mode=0700']


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


def copy_output(staging, folder):
    """The regular files the sandbox left (no links, no folders), at most MAX_COPIED_BYTES."""
    copied = 0
    for name in sorted(os.listdir(staging)):
        path = os.path.join(staging, name)
        if os.path.islink(path) or not os.path.isfile(path):
            continue
        size = os.path.getsize(path)
        if copied + size > MAX_COPIED_BYTES:
            continue
        shutil.copyfile(path, os.path.join(folder, name), follow_symlinks=False)
        copied += size


def unpack_output(stream_bytes, staging):
    """The regular files of the tar stream the container's trusted side sent, into staging."""
    try:
        with tarfile.open(fileobj=io.BytesIO(stream_bytes), mode='r:') as archive:
            for member in archive:
                if member.isfile() and os.path.basename(member.name) == member.name and member.name[:1] != '.':
                    with open(os.path.join(staging, member.name), 'wb') as target:
                        shutil.copyfileobj(archive.extractfile(member), target)
    except tarfile.TarError:
        pass   # the session broke down before it sent its folder: no result, the reason says why


def _read_at_most(pipe, kept, limit):
    """Everything from `pipe` until its end (so the writer never blocks), the first `limit` bytes
    kept in the bytearray `kept`."""
    for chunk in iter(lambda: pipe.read(65536), b''):
        kept += chunk[:max(0, limit - len(kept))]


def _limit_resources():
    """In the --no-container child: CPU seconds, file size, address space, open files."""
    for limit, value in ((resource.RLIMIT_CPU, 900), (resource.RLIMIT_FSIZE, 100 * 2 ** 20),
                         (resource.RLIMIT_AS, 4 * 2 ** 30), (resource.RLIMIT_NOFILE, 1024)):
        resource.setrlimit(limit, (value, value))


class Grader:
    def __init__(self, args, rubric, announce=True, on_step=None):
        self.args = args
        self.rubric = rubric
        self.announce = announce   # a line per graded student ("grade: [3/30] ...")
        self.on_step = on_step     # --no-container: called with each step the session reports, as it ends
        self.previous = {}         # folder name: the result of the last grading into the same --out
        self.out = os.path.abspath(args.out)
        self.run_id = uuid.uuid4().hex[:8]
        self.lock = threading.Lock()
        self.done = 0
        self.total = 0
        self.started = time.monotonic()
        # The build and every run of the lab at their limits: beyond this the sandbox is stopped.
        self.wall_limit = wall_limit.of_rubric(rubric)

    def grade_all(self, submissions):
        self.total = len(submissions)
        with ThreadPoolExecutor(max_workers=self.args.jobs) as pool:
            return list(pool.map(self.grade_one, submissions))

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
        result.update(seconds=time.monotonic() - started, student=who.name, student_id=who.id, folder=student)
        results.write(result, folder)   # the grade as the reports have it (checked against the rubric)
        gradescope.write(result, folder)
        with self.lock:
            self.done += 1
            if not self.announce:
                return result
            print('grade: [%d/%d] %s: %g / %g (%.0f s)%s%s' % (
                self.done, self.total, terminal_text(who.name + (' (%s)' % who.id if who.id else '')),
                result['score'], result['max_score'], result['seconds'],
                ': ' + terminal_text(result['error']) if result.get('error') else '',
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
        if self.args.rubric:
            args += ['--rubric', os.path.abspath(self.args.rubric) if self.args.no_container else '/rubric.yaml']
        if getattr(self.args, 'only', None):
            args += ['--only', self.args.only]
        return args

    def _run_in_container(self, submission, package, student, staging):
        """The trusted side (the session, the ROS master, the simulators) as root without privileges, the
        student's side as `student`; the result comes back on the container's standard output."""
        name = 'course-grader-%s-%s-%s' % (self.run_id, ascii_name(student)[:40], uuid.uuid4().hex[:6])
        rubric_mount = ['-v', '%s:/rubric.yaml:ro' % os.path.abspath(self.args.rubric)] if self.args.rubric else []
        # --init: a reaper as PID 1, so that what the submission forks and leaves behind is reaped.
        # --rm as well as the rm -f below: the engine removes it even if this process is killed.
        command = ['docker', 'run', '--rm', '--name', name, '--init', '--network', 'none', '--user', 'root',
                   '--read-only', '--security-opt', 'no-new-privileges'] + TRUSTED_CAPABILITIES + [
                   '-e', 'HOME=/grader', '-e', 'ROS_HOME=/grader/ros',
                   '-v', '%s:/submission:ro' % submission] + rubric_mount + CONTAINER_LIMITS + [
                   self.args.image, 'bash', '-c', 'source tools/env.sh && exec ' + ' '.join(SESSION) + ' "$@"',
                   'grade_submission', '--student-user', 'student',
                   '--send'] + self._session_args('/submission/' + package, '/grader/out', '/tmp/student', student)

        def stop(process):   # whatever happened: the container and everything in it are gone
            subprocess.run(['docker', 'rm', '-f', name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            # rm -f answers at once while the engine is still removing it for --rm (seen under load):
            # gone means the engine no longer knows the name.
            poll_until(lambda: subprocess.run(['docker', 'container', 'inspect', name], stdout=subprocess.DEVNULL,
                                              stderr=subprocess.DEVNULL).returncode != 0, 60, poll=0.2)
            if process.poll() is None:
                process.kill()
                process.wait()
        return self._run_session(command, staging, stop)

    def _run_on_host(self, submission, package, student, staging, scratch):
        """The session on this machine, as our user: the student's side apart only in its
        environment (no overlay on the trusted side), its process groups and its folder, and the
        result read from the session's standard output, as from a container (docs/grading.md)."""
        from course_common.processes import stop_process_group
        mark = '%s-%s' % (self.run_id, uuid.uuid4().hex)
        env = dict(os.environ, ROS_HOME=os.path.join(scratch, 'ros'))
        env[RUN_MARK] = mark
        # The session's output folder and the student's side's folder: apart from each other and
        # from the grader's scratch (the submission, what comes back).
        session_out = tempfile.mkdtemp(prefix='course-grader-session-')
        student_scratch = tempfile.mkdtemp(prefix='course-grader-student-')
        argv = SESSION + ['--send'] + self._session_args(
            os.path.join(submission, package), session_out, student_scratch, student)

        def stop(process):
            stop_process_group(process, 10)
            # The session stops what it started; what escaped it (a node in a session of its
            # own, reparented to init) carries the mark in its environment and goes now.
            stop_marked('%s=%s' % (RUN_MARK, mark))
        try:
            return self._run_session(argv, staging, stop, env=env, start_new_session=True,
                                     preexec_fn=_limit_resources)
        finally:
            for folder in (session_out, student_scratch):
                shutil.rmtree(folder, ignore_errors=True)

    def _run_session(self, argv, staging, stop, **popen_args):
        """A grading session (grade_submission --send): its log (standard error) into
        staging/grader.txt, each step it reports to on_step as it comes, and the output folder it
        sends as a tar stream on standard output unpacked into staging. stop(process) ends it,
        whatever happened. Returns why there is no result, or None."""
        log = os.path.join(staging, 'grader.txt')
        sent = bytearray()
        with open(log, 'wb') as stream:
            process = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                       stderr=subprocess.PIPE if self.on_step else stream, **popen_args)
            reader = threading.Thread(target=_read_at_most, args=(process.stdout, sent, MAX_COPIED_BYTES + 2 ** 20),
                                      daemon=True)
            reader.start()
            copier = None
            if self.on_step:
                copier = threading.Thread(target=self._copy_steps, args=(process.stderr, stream), daemon=True)
                copier.start()
            try:
                code = process.wait(self.wall_limit)
            except subprocess.TimeoutExpired:
                code = None
            finally:
                stop(process)
                reader.join(10)
                if copier:
                    copier.join(10)
        unpack_output(bytes(sent), staging)
        return self._reason(code, log)

    def _copy_steps(self, pipe, stream):
        """The session's output into its log, and each step it reports to on_step as it comes."""
        for line in pipe:
            stream.write(line)
            stream.flush()
            text = line.decode(errors='replace').rstrip()
            if text.startswith(STEP_PREFIX):
                self.on_step(text[len(STEP_PREFIX):])

    def _reason(self, code, log):
        if code is None:
            return 'the grading did not end within %d s and was stopped' % self.wall_limit
        if code == 137:
            return 'the sandbox was killed (out of memory, %s): %s' % (CONTAINER_LIMITS[1], feedback.log_tail(log, 3))
        if code != 0:
            return 'the grading stopped with exit status %d: %s' % (code, feedback.log_tail(log, 5))
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
        previous = prepare_out(args.out)
    except (rubrics.RubricError, GraderError, OSError) as error:
        print('grade: %s' % terminal_text(error), file=sys.stderr)
        return 2
    print('grade: %d submissions of %s, %d at a time%s' % (
        len(args.submissions), args.lab, args.jobs, '' if args.no_container else ', each in a container of '
        + args.image), flush=True)
    grader = Grader(args, rubric)
    grader.previous = previous
    class_results = grader.grade_all(args.submissions)
    seconds = time.monotonic() - started
    gone = sorted(set(previous) - {result['folder'] for result in class_results})
    if gone:
        print('grade: graded last time into %s, not this time: %s' % (args.out, ', '.join(
            '%s (%g / %g)' % (terminal_text(previous[f]['student']), previous[f]['score'], previous[f]['max_score'])
            for f in gone)))
    reports.write_all(class_results, rubric, grader.out, seconds, previous)
    print('grade: %d students graded in %.0f s (%.1f s per student): %s, %s, %s' % (
        len(class_results), seconds, seconds / len(class_results), os.path.join(args.out, 'grades.csv'),
        os.path.join(args.out, 'report.html'), os.path.join(args.out, 'junit/')), flush=True)
    return 0
