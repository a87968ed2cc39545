"""One grading session (course_grader.grading_session) run in its sandbox, timed out and stopped,
and what it sent back: the one way ./grade.sh, the student's check and both platforms run a grading.

Three sandboxes, one session: `in_container` (./grade.sh: a container of the course's image, the
trusted side root without privileges, the student's side the user `student`), `on_host` (./grade.sh
--no-container and the check: a process group of our own user, with resource limits only) and
`in_place` (the platforms: we are the trusted side of the course's image already, as root). In each
the session sends its output folder as a tar stream on its standard output, which no process of the
student's holds, and this side keeps only the regular files of it.

The sandbox's numbers are written here once: the container's options (the platforms' workflow
starts its container with the same, platform_files.py) and the limits of the other two."""
import contextlib
import io
import os
import pwd
import resource
import shutil
import signal
import subprocess
import tarfile
import tempfile
import threading
import uuid
from dataclasses import dataclass
from typing import Callable, Optional

from course_common.process_table import proc_fd, stop_marked, stop_user
from course_common.processes import stop_process_group
from course_common.waiting import poll_until
from course_grader import feedback
from course_grader.labs import wall_limit_of
from course_grader.results import RESULT_FILE
from course_grader.submission import ascii_name

# The session, by its module: rosrun's look-up costs half a second.
SESSION = ['/usr/bin/python3', '-m', 'course_grader.grading_session']
STEP_PREFIX = 'grade_submission: '   # a line of the session that reports a step and its time
RUN_MARK = 'COURSE_GRADER_RUN'       # in the environment of everything an on_host session starts
MAX_COPIED_BYTES = 50 * 2 ** 20      # of what one sandbox sends back

MEMORY = '1536m'                     # of the container, swap included
PROCESSES = 512                      # processes and threads of the container
CPUS = 1
OPEN_FILES = 1024                    # per process
FILE_BYTES = 100 * 2 ** 20           # the largest file a process may write
CPU_SECONDS = 900                    # on_host and in_place, per process (a container has CPUS instead)
ADDRESS_BYTES = 4 * 2 ** 30          # on_host and in_place, per process (a container has MEMORY instead)

# The trusted side of a container is root with no capability but these: start the student's side
# as the user `student`, and stop it. No write access anywhere else, no other user's processes.
TRUSTED_CAPABILITIES = ['--cap-drop', 'ALL', '--cap-add', 'SETUID', '--cap-add', 'SETGID', '--cap-add', 'KILL']
# --init: a reaper as PID 1, so that what the submission forks and leaves behind is reaped.
# --rm: the engine removes the container even if this process is killed.
CONTAINER_BASE = ['--rm', '--init', '--network', 'none', '--user', 'root', '--read-only',
                  '--security-opt', 'no-new-privileges']
CONTAINER_ENV = ['-e', 'HOME=/grader', '-e', 'ROS_HOME=/grader/ros']
CONTAINER_LIMITS = ['--memory', MEMORY, '--memory-swap', MEMORY, '--pids-limit', str(PROCESSES),
                    '--cpus', str(CPUS), '--ulimit', 'nofile=%d:%d' % (OPEN_FILES, OPEN_FILES),
                    '--ulimit', 'fsize=%d' % FILE_BYTES,
                    '--tmpfs', '/tmp:rw,exec,nosuid,nodev,size=512m',
                    # The trusted side's own disk: a submission that fills /tmp cannot stop its logs.
                    '--tmpfs', '/grader:rw,noexec,nosuid,nodev,size=128m,mode=0700']


def container_options():
    """The options of the `docker run` of a grading, before its name and mounts (one list of words)."""
    return CONTAINER_BASE + TRUSTED_CAPABILITIES + CONTAINER_ENV + CONTAINER_LIMITS


def limit_resources():
    """In a session started on_host or in_place (the child, before it runs): CPU seconds, file
    size, address space, open files."""
    for limit, value in ((resource.RLIMIT_CPU, CPU_SECONDS), (resource.RLIMIT_FSIZE, FILE_BYTES),
                         (resource.RLIMIT_AS, ADDRESS_BYTES), (resource.RLIMIT_NOFILE, OPEN_FILES)):
        resource.setrlimit(limit, (value, value))


@dataclass(frozen=True)
class Options:
    """How the sessions of one grading run: `image` the course's image (None: on this machine,
    without isolation), `rubric_file` a teacher's own rubric (None: the lab's), `only` one
    criterion's checks, `on_step` called with each step a session reports, as it ends. On this
    machine only (on_host: the student's check), `build_cache` a folder of ours where the build is
    kept for the next session of the lab and `build_jobs` the compilations at once
    (grading_session.build)."""
    image: Optional[str] = None
    rubric_file: Optional[str] = None
    only: Optional[str] = None
    on_step: Optional[Callable[[str], None]] = None
    build_cache: Optional[str] = None
    build_jobs: int = 1


@dataclass(frozen=True)
class Grading:
    """One session to run: the rubric, the submission's folder (unpacked, ours to read) and its
    package's folder within it, the student's name, and `staging`, an empty folder of ours that
    receives the regular files the session sends (its grader.txt log among them)."""
    rubric: object
    submission: str
    package: str
    student: str
    staging: str


def session_args(grading, options, package_dir, out, scratch, rubric_path=None):
    """The session's arguments after its command: `package_dir`, `out` and `scratch` as the session
    sees them; `rubric_path` the teacher's rubric as it sees it."""
    args = ['--lab', grading.rubric.lab, '--package', package_dir, '--out', out, '--scratch', scratch,
            '--student', grading.student, '--send']
    if options.rubric_file:
        args += ['--rubric', rubric_path or os.path.abspath(options.rubric_file)]
    if options.only:
        args += ['--only', options.only]
    return args


def run(grading, options):
    """The grading's session in its sandbox (a container with options.image, else on this machine);
    returns why there is no result (a sentence), or None."""
    if options.image:
        return in_container(grading, options)
    return on_host(grading, options)


def in_container(grading, options):
    """The trusted side (the session, the ROS master, the simulators) as root without privileges, the
    student's side as `student`; the submission mounted read-only."""
    name = 'course-grader-%s-%s' % (ascii_name(grading.student)[:40], uuid.uuid4().hex[:12])
    rubric_mount = ['-v', '%s:/rubric.yaml:ro' % os.path.abspath(options.rubric_file)] if options.rubric_file else []
    command = (['docker', 'run'] + CONTAINER_BASE[:1] + ['--name', name] + CONTAINER_BASE[1:] + TRUSTED_CAPABILITIES
               + CONTAINER_ENV + ['-v', '%s:/submission:ro' % grading.submission] + rubric_mount + CONTAINER_LIMITS
               + [options.image, 'bash', '-c', 'source tools/env.sh && exec ' + ' '.join(SESSION) + ' "$@"',
                  'grade_submission', '--student-user', 'student']
               + session_args(grading, options, '/submission/' + grading.package, '/grader/out', '/tmp/student',
                              '/rubric.yaml'))

    # Whatever happened: the container and everything in it are gone.
    return _run_session(command, grading, options, lambda process: stop_container(name, process))


def stop_container(name, process):
    """The container `name` and `process`, the `docker run` that started it, gone, whatever they were doing."""
    subprocess.run(['docker', 'rm', '-f', name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    # rm -f answers at once while the engine is still removing it for --rm (seen under load):
    # gone means the engine no longer knows the name.
    poll_until(lambda: subprocess.run(['docker', 'container', 'inspect', name], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL).returncode != 0, 60, poll=0.2)
    if process.poll() is None:
        process.kill()
        process.wait()


def on_host(grading, options):
    """The session on this machine, as our user: the student's side apart only in its environment
    (no overlay on the trusted side), its process groups and its folder (docs/grading.md)."""
    mark = uuid.uuid4().hex
    # The session's output folder and the student's side's folder: apart from each other and from
    # the caller's (the submission, what comes back).
    session_out = tempfile.mkdtemp(prefix='course-grader-session-')
    student_scratch = tempfile.mkdtemp(prefix='course-grader-student-')
    ros_home = tempfile.mkdtemp(prefix='course-grader-ros-')
    env = dict(os.environ, ROS_HOME=ros_home, **{RUN_MARK: mark})
    argv = SESSION + session_args(grading, options, os.path.join(grading.submission, grading.package),
                                  session_out, student_scratch)
    if options.build_cache:
        argv += ['--build-cache', options.build_cache]
    if options.build_jobs > 1:
        argv += ['--build-jobs', str(options.build_jobs)]

    def stop(process):
        stop_process_group(process, 10)
        # The session stops what it started; what escaped it (a node in a session of its own,
        # reparented to init) carries the mark in its environment and goes now.
        stop_marked('%s=%s' % (RUN_MARK, mark))
    try:
        return _run_session(argv, grading, options, stop, env=env, start_new_session=True,
                            preexec_fn=limit_resources)
    finally:
        for folder in (session_out, student_scratch, ros_home):
            shutil.rmtree(folder, ignore_errors=True)


def in_place(grading, options, work, student_user='student'):
    """The session started by the trusted side of the course's image (we are root there), the
    student's side as `student_user`; `work` our own folder (the session's logs and result: no
    process of the student's side can write there)."""
    out = tempfile.mkdtemp(prefix='course-grader-', dir=work)
    # A new name: the session makes it, open to the student's side (sticky).
    scratch = os.path.join(tempfile.gettempdir(), 'course-student-%s' % uuid.uuid4().hex[:8])
    argv = SESSION + ['--student-user', student_user] + session_args(
        grading, options, os.path.join(grading.submission, grading.package), out, scratch)
    env = dict(os.environ, HOME=out, ROS_HOME=os.path.join(out, 'ros'))
    # The descriptor of /proc handed down where there is none (Gradescope's chroot), so that the
    # session can stop the student's processes between its steps (course_common.process_table).
    handed_down = () if proc_fd() is None else (proc_fd(),)

    def stop(process):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        stop_user(pwd.getpwnam(student_user).pw_uid)
    try:
        return _run_session(argv, grading, options, stop, env=env, start_new_session=True,
                            preexec_fn=limit_resources, pass_fds=handed_down)
    finally:
        for folder in (out, scratch):
            shutil.rmtree(folder, ignore_errors=True)


def _run_session(argv, grading, options, stop, **popen_args):
    """The session started with `argv`: its log (standard error) into staging/grader.txt, each step it
    reports to options.on_step as it comes, the tar stream it sends on standard output unpacked into
    staging. stop(process) ends it, whatever happened. Returns why there is no result, or None."""
    log = os.path.join(grading.staging, 'grader.txt')
    sent = bytearray()
    with open(log, 'wb') as stream:
        process = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   **popen_args)
        readers = [threading.Thread(target=read_at_most, args=(process.stdout, sent, MAX_COPIED_BYTES + 2 ** 20),
                                    daemon=True),
                   threading.Thread(target=copy_steps, args=(process.stderr, stream, options.on_step), daemon=True)]
        for reader in readers:
            reader.start()
        limit = None
        try:
            # Worked out once the session runs: it imports the lab's module (ROS), up to 0.7 s.
            limit = wall_limit_of(grading.rubric)
            code = process.wait(limit)
        except subprocess.TimeoutExpired:
            code = None
        finally:
            stop(process)
            for reader in readers:
                reader.join(10)
    unpack_output(bytes(sent), grading.staging)
    return reason(code, log, limit)


def reason(code, log, limit):
    """Why a session that ended with `code` (None: stopped at the wall limit `limit`) left no
    result, or None when it ended well."""
    if code is None:
        return 'the grading did not end within %d s and was stopped' % limit
    if code == 137:
        return 'the sandbox was killed (out of memory, %s): %s' % (MEMORY, feedback.log_tail(log, 3))
    if code != 0:
        return 'the grading stopped with exit status %d: %s' % (code, feedback.log_tail(log, 5))
    return None


def copy_steps(pipe, stream, on_step=None):
    """The session's log into `stream`, and each step it reports to on_step as it comes."""
    for line in pipe:
        stream.write(line)
        stream.flush()
        text = line.decode(errors='replace').rstrip()
        if on_step and text.startswith(STEP_PREFIX):
            on_step(text[len(STEP_PREFIX):])


def read_at_most(pipe, kept, limit):
    """Everything from `pipe` until its end (so the writer never blocks), the first `limit` bytes
    kept in the bytearray `kept`."""
    for chunk in iter(lambda: pipe.read(65536), b''):
        kept += chunk[:max(0, limit - len(kept))]


def unpack_output(stream_bytes, staging):
    """The regular files of the tar stream the session sent, into staging."""
    try:
        with tarfile.open(fileobj=io.BytesIO(stream_bytes), mode='r:') as archive:
            for member in archive:
                if member.isfile() and os.path.basename(member.name) == member.name and member.name[:1] != '.':
                    with open(os.path.join(staging, member.name), 'wb') as target:
                        shutil.copyfileobj(archive.extractfile(member), target)
    except tarfile.TarError:
        pass   # the session broke down before it sent its folder: no result, the reason says why


def copy_output(staging, folder):
    """The regular files the sandbox sent (no links, no folders), at most MAX_COPIED_BYTES."""
    copied = 0
    # The result first: whatever else the session sent (its runs' bags, pictures) comes within what is left.
    for name in sorted(os.listdir(staging), key=lambda name: (name != RESULT_FILE, name)):
        path = os.path.join(staging, name)
        if os.path.islink(path) or not os.path.isfile(path):
            continue
        size = os.path.getsize(path)
        if copied + size > MAX_COPIED_BYTES:
            continue
        shutil.copyfile(path, os.path.join(folder, name), follow_symlinks=False)
        copied += size
