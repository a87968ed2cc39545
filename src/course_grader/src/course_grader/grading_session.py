"""The grading of one submission, inside its sandbox: the trusted side (this process, the ROS master,
the simulators, the checks, with the course's environment only) and the student's side (the build and
the student's nodes, with the student's overlay, as another user when the sandbox allows it) stand
apart; only the trusted side writes the result, logs and pictures.

In a container this process runs as root with no capability but to switch users and to stop the
student's processes, and the student's side runs as the user `student`: it cannot write the output
folder, nor signal or trace this process, the master or the simulators. The result leaves as a tar
stream on this process's standard output, which no process of the student's holds."""
import argparse
import fcntl
import filecmp
import functools
import hashlib
import os
import shutil
import pwd
import subprocess
import sys
import tarfile
import time
import uuid
from concurrent.futures import ThreadPoolExecutor

from course_common import sim_record
from course_checks.launch import Launch
from course_grader import bags, feedback, labs, results, rubric as rubrics, wall_limit
from course_common.process_table import NoProcessTable, UserReaper, listening_sockets, socket_inodes, stop_user
from course_common.processes import together
from course_common.waiting import poll_until
from course_grader.results import Verdict


# Before each program of the student's side: the kernel's out-of-memory killer takes it first
# (oom_score_adj 1000, the most; raising it needs no privilege). A submission that fills its
# sandbox's memory then loses its own processes, not the session, the master or the simulators,
# and each run keeps its own verdict. It may lower the score back (no capability pins it): then
# the session may be killed instead, which costs that submission's whole grade and no one else's.
# Where there is no /proc (Gradescope's chroot) choom cannot work: the kernel then goes by size alone.
OOM_KILLED_FIRST = ['/usr/bin/choom', '-n', '1000', '--']
OOM_SCORE = '/proc/self/oom_score_adj'


class StudentSide:
    """How the student's build and nodes are started: as `user` (None: as we are), with the
    course's environment plus, once built, the student's overlay, each the first that the kernel
    kills when memory runs out (OOM_KILLED_FIRST)."""

    def __init__(self, user, scratch):
        self.user = user
        self.scratch = scratch
        self.home = os.path.join(scratch, 'home')
        self.env = dict(os.environ, HOME=self.home, ROS_HOME=os.path.join(scratch, 'ros_home'))
        self.prefix = OOM_KILLED_FIRST if os.path.exists(OOM_SCORE) and os.path.exists(OOM_KILLED_FIRST[0]) else []
        # Started now, while the user has no process: a fork bomb may leave no room for a program later.
        self.reaper = UserReaper(pwd.getpwnam(user).pw_uid) if user else None

    def start(self, argv, log_path, cwd=None):
        return Launch(self.prefix + list(argv), log_path, env=self.env, user=self.user, cwd=cwd)

    def run(self, argv, timeout, env=None, cwd=None):
        """What a short command printed (standard output); with `env` instead of the side's own."""
        as_user = {'user': self.user, 'group': self.user, 'extra_groups': []} if self.user else {}
        return subprocess.run(self.prefix + list(argv), env=self.env if env is None else env, cwd=cwd,
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, timeout=timeout, check=True, **as_user).stdout

    def stop_all(self):
        """Every process of the student's user, after the build and after each run: a daemon the
        build or a run started (in a session of its own) does not live into the next run. As
        ourselves (--no-container) there is no telling them from ours: the grader's mark stops
        them after the session."""
        if self.user:
            stop_user(pwd.getpwnam(self.user).pw_uid, self.reaper)


class Session:
    """What the lab's checks need: the package's folder, the rubric, the output folder, and the
    two ways to start a program: on the student's side or on the trusted side."""

    def __init__(self, rubric, package_dir, out_dir, student_side, only=None):
        self.rubric = rubric
        self.package_dir = package_dir
        self.out_dir = out_dir
        # A folder in the output folder: the result carries the files at its top only (send_folder).
        self.records_dir = os.path.join(out_dir, 'records')
        self.student_side = student_side
        self.only = only   # a criterion id: the runs that judge other criteria are left out
        self.pictures = []
        self.bags_dir = out_dir   # each run's bag and its marks (course_grader.bags), sent with the result
        self.notes = []   # sentences on the grading that decide no criterion (a run's bag not kept)
        self.turtlesim_nodes = {}   # (launch file, args): what it declares of turtlesim (labs.turtlesim_runs)

    def script(self, name):
        """Path of a student's script by file name (scripts/ first), or None."""
        from course_grader.submission import find_file
        hits = find_file(self.package_dir, name)
        return os.path.join(self.package_dir, hits[0]) if hits else None

    def relative(self, path):
        return os.path.relpath(path, os.path.dirname(self.package_dir))

    def log_path(self, name):
        return os.path.join(self.out_dir, name)

    def student(self, argv, log_name):
        """One of the student's programs (a script, a roslaunch of the student's package)."""
        return self.student_side.start(argv, self.log_path(log_name))

    def trusted(self, argv, log_name, record=None):
        """A program of the course (a simulator), with the course's environment only; with
        `record`, the simulator records what it does into that file (course_common.sim_record)."""
        env = dict(os.environ, **{sim_record.ENVIRONMENT: record}) if record else None
        return Launch(argv, self.log_path(log_name), env=env)

    def record_path(self, name):
        """A new file for a simulator's record, in the trusted side's own folder (the student's
        side can neither read nor write it) but not in the result."""
        os.makedirs(self.records_dir, mode=0o700, exist_ok=True)
        path = os.path.join(self.records_dir, '%s.record' % name)
        if os.path.lexists(path):   # of a simulator prepared before for the same run, which never ran
            os.remove(path)
        return path

    def keep_run(self, name, messages):
        """The run `name` as <name>.bag (course_grader.bags), from messages() (the simulators'
        records converted), within bags.BAG_SECONDS. One that cannot be made or written (a full
        disk) is a note, named in the log too: the run's criteria stand either way."""
        path = os.path.join(self.bags_dir, name + bags.BAG_SUFFIX)
        deadline = time.monotonic() + bags.BAG_SECONDS
        try:
            bags.write_bag(path, messages(), deadline)
        except Exception as error:   # noqa: B902 (a full disk, a record cut short: the grade stands)
            self.note('the run %s was not kept as %s (%s); its criteria stand' % (
                name, os.path.basename(path), str(error)[:300] or type(error).__name__))

    def keep_marks(self, name, marks):
        """The moments the checks judged in the run `name` ([bags.mark]) as <name>.marks.json."""
        path = os.path.join(self.bags_dir, name + bags.MARKS_SUFFIX)
        try:
            bags.write_marks(path, marks)
        except Exception as error:   # noqa: B902 (as keep_run)
            self.note('the moments judged in the run %s were not kept (%s); its criteria stand' % (
                name, str(error)[:300] or type(error).__name__))

    def note(self, sentence):
        """A sentence on the grading that decides no criterion: in the result's notes and the log."""
        self.notes.append(sentence)
        print('grade_submission note: %s' % sentence, file=sys.stderr, flush=True)

    def picture(self, name):
        """Where a simulator of the trusted side saves the picture `name`."""
        self.pictures.append(name)
        return self.log_path(name)


def run_logged(side, argv, log_path, timeout, cwd=None):
    """Run a command on the student's side, its output to log_path; on timeout stop its group.
    Returns the exit code, or None when the time limit was reached."""
    run = side.start(argv, log_path, cwd=cwd)
    try:
        run.process.wait(timeout)
    except subprocess.TimeoutExpired:
        run.stop(5)
        return None
    run.stop(5)
    return run.process.returncode


# What decides how catkin_make configures a package: a change to one of these (or to the list of the
# package's files) and a kept build (BuildCache) is thrown away, the package built afresh.
BUILD_DESCRIPTION = ('CMakeLists.txt', 'package.xml', 'setup.py')
BUILD_DESCRIPTION_FOLDERS = ('msg', 'srv', 'action', 'cfg')


class BuildCache:
    """The student's check only (on this machine, as the student): the workspace of the last check
    of this lab kept in `folder`, so that catkin_make builds only what changed since, as the
    student's own catkin_make does. It is used while the package's files are the same by name and
    its build description (BUILD_DESCRIPTION, msg/, srv/, ...) the same to the byte: only the
    contents of sources, scripts and launch files may differ, which make rebuilds from their
    dates. A build that fails there is done again afresh in the emptied cache (the verdict and its
    sentence are a fresh build's, as the teacher's run has them), unless it began from an empty
    workspace; what a failed build compiled is kept (not after a timeout), so that the check after
    the student's fix builds only the files fixed. Held by one session at a time (a lock); another
    one builds afresh in its scratch folder."""

    def __init__(self, folder):
        self.folder = os.path.abspath(folder)
        self.workspace = os.path.join(self.folder, 'ws')
        self.fresh = True   # whether prepare() began from an empty workspace
        self._lock = None

    def acquire(self):
        """Whether this session holds the cache (kept until the session's process ends)."""
        try:
            os.makedirs(self.folder, mode=0o700, exist_ok=True)
            lock = open(os.path.join(self.folder, 'lock'), 'w')
        except OSError:
            return False
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            lock.close()
            return False
        self._lock = lock
        return True

    @staticmethod
    def key(package_dir):
        """The package's file names and its build description's contents, as one digest; None for a
        package holding anything but folders and regular files (a link: built afresh)."""
        digest = hashlib.sha256()
        for root, folders, files in os.walk(package_dir):
            folders.sort()
            for name in folders + files:
                if os.path.islink(os.path.join(root, name)):
                    return None
            for name in sorted(files):
                path = os.path.join(root, name)
                relative = os.path.relpath(path, package_dir)
                digest.update(b'F' + relative.encode(errors='surrogateescape') + b'\0')
                top = relative.split(os.sep)[0]
                if relative in BUILD_DESCRIPTION or top in BUILD_DESCRIPTION_FOLDERS or name.endswith('.cmake'):
                    with open(path, 'rb') as stream:
                        digest.update(hashlib.sha256(stream.read()).digest())
        return digest.hexdigest()

    def prepare(self, package_dir, package):
        """The kept workspace with the package's files as they are now (files whose contents
        changed copied, so dated now; the others untouched), or an empty one; its folder, or None
        when the package cannot be kept (BuildCache.key)."""
        key = self.key(package_dir)
        if key is None:
            return None
        key_file = os.path.join(self.folder, 'key')
        try:
            with open(key_file) as stream:
                kept = stream.read().strip() == key
        except OSError:
            kept = False
        target = os.path.join(self.workspace, 'src', package)
        self.fresh = not kept or not os.path.isdir(target)
        if self.fresh:
            self.clear()
            os.makedirs(os.path.join(self.workspace, 'src'))
        for root, folders, files in os.walk(package_dir):
            here = os.path.join(target, os.path.relpath(root, package_dir))
            os.makedirs(here, exist_ok=True)
            for name in files:
                source, copy = os.path.join(root, name), os.path.join(here, name)
                if not (os.path.isfile(copy) and filecmp.cmp(source, copy, shallow=False)):
                    shutil.copy(source, copy)   # a new date: make rebuilds what depends on it
                elif os.stat(source).st_mode != os.stat(copy).st_mode:
                    shutil.copymode(source, copy)
        with open(key_file, 'w') as stream:
            stream.write(key + '\n')
        return self.workspace

    def clear(self):
        for name in ('key', 'ws'):
            path = os.path.join(self.folder, name)
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path)
            elif os.path.lexists(path):
                os.remove(path)


def build(session, scratch, cache=None, jobs=1):
    """catkin_make of the student's package in scratch/ws (an overlay of the course workspace), on
    the student's side, `jobs` compilations at once; with `cache` (BuildCache, the student's check),
    in the workspace kept there when it can. Returns the environment of the built overlay, or
    raises BuildFailed."""
    if cache is not None and cache.acquire():
        for attempt in ('as kept', 'afresh'):
            if attempt == 'afresh':
                # A failure from a kept build: the verdict and its sentence are those of a fresh
                # build, made in the emptied cache.
                cache.clear()
            try:
                workspace = cache.prepare(session.package_dir, session.rubric.package)
            except OSError:   # a full disk, a file it cannot read: built afresh, as without a cache
                workspace = None
            if workspace is None:
                break
            try:
                return _build(session, workspace, None, jobs)
            except BuildFailed as failed:
                # A build stopped at its time limit may leave half-written objects: none is kept,
                # nor built again (a second build would take the session beyond its wall limit).
                if failed.timed_out:
                    cache.clear()
                # A build begun from nothing is a fresh build already: what it compiled is kept,
                # so that the check after the student's fix builds only what changed.
                if cache.fresh or failed.timed_out:
                    raise
    return _build(session, os.path.join(scratch, 'ws'), session.package_dir, jobs)


def _build(session, workspace, copy_from, jobs):
    """catkin_make in `workspace`, after copying the package from `copy_from` (None: it is there)."""
    side = session.student_side
    package = os.path.join(workspace, 'src', session.rubric.package)
    log = session.log_path('build.log')
    seconds = session.rubric.limits['build_seconds']
    # ROS_HOME made here, by the student's user: rospy would give a log folder it makes the owner of
    # its parent (root's scratch folder), fail to, and print a warning into every node's output.
    # No build type, as the student's own catkin_make: unoptimised C++ builds in 80 % of the time.
    copy = 'cp -R "$4" "$5" && ' if copy_from else ''
    code = run_logged(side, ['bash', '-c', 'mkdir -p "$1" "$2" "$3/src" && %sexec catkin_make '
                             '--directory "$3" -DPYTHON_EXECUTABLE=/usr/bin/python3 -j%d' % (copy, jobs),
                             'build', side.home, side.env['ROS_HOME'], workspace,
                             copy_from or '', package],
                      log, seconds)
    if code != 0:
        with open(log, errors='replace') as stream:
            text = stream.read()
        if code is None:
            raise BuildFailed('catkin_make did not finish within %d s' % seconds, timed_out=True)
        raise BuildFailed(feedback.first_compiler_error(text) or 'catkin_make failed (exit %d): see build.log' % code)
    session.package_dir = package
    listing = side.run(['bash', '-c', 'source "$1/devel/setup.bash" && env -0', 'env', workspace],
                       wall_limit.STEP_SECONDS)
    return dict(item.split('=', 1) for item in listing.decode(errors='replace').split('\0') if '=' in item)


class BuildFailed(Exception):
    def __init__(self, reason, timed_out=False):
        super().__init__(reason)
        self.timed_out = timed_out


def core_parameters():
    """/rosversion and /rosdistro as roscore.xml sets them: what `rosversion roslaunch` and
    `rosversion -d` print, the newline included."""
    import rospkg.rosversion
    version = rospkg.rosversion.get_version_from_package_name('roslaunch') or '<unversioned>'
    distro = (os.environ.get('ROS_DISTRO') or rospkg.rosversion.get_distro_name_from_roscore() or 'Debian')
    return {'/rosversion': version + '\n', '/rosdistro': distro + '\n'}


# Master.ready's wait: our rosmaster ended before it listened, or another program listens on its port.
ENDED, TAKEN = 'ended', 'taken'
# Master._listener: the kernel's table names our rosmaster's socket, or cannot be read.
OURS, UNKNOWN = 'ours', 'unknown'


class Master:
    """A ROS master of our own on a free port: rosmaster alone (roscore's roslaunch and rosout
    cost a second at the start and more at the end, and nothing of the grading reads /rosout),
    started at once so that it comes up while the student's package builds; ready() waits for it
    and starts the grader's own rospy node on it. The trusted side's programs started from now on
    (the simulators prepared during the build) have its address."""

    def __init__(self, log_path):
        from course_common.processes import free_port
        self.port = free_port()
        # 127.0.0.1, not localhost: localhost may be ::1 first, a port of its own that anyone may
        # listen on while our master holds the IPv4 one.
        self.uri = 'http://127.0.0.1:%d' % self.port
        self.process = Launch(['rosmaster', '--core', '-p', str(self.port)], log_path)
        os.environ['ROS_MASTER_URI'] = self.uri

    def ready(self):
        import rosgraph
        import rospy
        master = rosgraph.Master('/course_grader')
        answering = poll_until(lambda: self._answering(master), 60, poll=0.05)
        if answering != self.process.process.pid:
            raise RuntimeError('the ROS master did not start on port %d%s' % (
                self.port, ' (another program took the port first)' if answering == TAKEN else ''))
        master.setParam('/run_id', str(uuid.uuid1()))   # as roscore sets it (roslaunch reads it)
        for name, value in core_parameters().items():   # the student's roslaunch does not set them
            master.setParam(name, value)
        master.setParam('/use_sim_time', False)
        rospy.init_node('course_grader', disable_signals=True)

    def _answering(self, master):
        """Our rosmaster's process id once it answers on the port; None until then; ENDED, TAKEN.

        The port was free when chosen, not reserved: a program that listens there first (the
        student's build reads the port on rosmaster's command line and starts a master of its own,
        or another grading on this machine does) would answer too, and what it answers, its process
        id included, is its own to say. So the socket that listens on the port must be one our
        process holds (the kernel's word); then no other program can listen there. Where the
        kernel's table cannot be read (no /proc), the answer's process id is all there is."""
        if self.process.ended():
            return ENDED
        listener = self._listener()
        if listener is None or listener == TAKEN:
            return listener
        try:
            return master.getPid()
        except Exception:   # not up yet
            return None

    def _listener(self):
        """Who listens on the port by the kernel's table: OURS, TAKEN (a socket our rosmaster does
        not hold), None (no one), or UNKNOWN where there is no table to read."""
        try:
            listening = listening_sockets(self.port)
        except NoProcessTable:
            return UNKNOWN
        if not listening:
            return None
        return TAKEN if listening - socket_inodes(self.process.process.pid) else OURS

    def lost(self):
        """None while the master is still the one ready() accepted and the grader's own node on it
        runs; else what became of them. A node of the submission can reach both: shut the master
        down through its API and listen on the freed port itself (what answers there then, who
        publishes what, the simulator's parameters, is not the master's word), or shut the grader's
        node down through its slave API (the grader's own publishers, the turn of laser_data say,
        then send nothing). Where the kernel's table cannot be read, only the master's end is seen."""
        import rospy
        if self.process.ended():
            return 'the ROS master stopped'
        listener = self._listener()
        if listener == TAKEN:
            return 'another program than the ROS master listened on its port'
        if listener is None:
            return 'the ROS master no longer listened on its port'
        if rospy.core.is_shutdown():
            return "the grader's own ROS node was shut down"
        return None

    def stop(self):
        import rospy
        # Together: rospy's own shutdown waits on its threads for half a second.
        together(functools.partial(rospy.signal_shutdown, 'graded'), functools.partial(self.process.stop, 15))


def grade(rubric, package_dir, out_dir, scratch, student, student_user=None, only=None, deliver=None,
          build_cache=None, build_jobs=1):
    """The result of the submission. deliver(result), when given, is called with it before the master
    stops (the sandbox may end there: what is left of the trusted side ends with it). `build_cache`
    (a folder: the student's check only) and `build_jobs`: how the package is built (build)."""
    started = time.monotonic()
    side = StudentSide(student_user, scratch)   # its environment made before the master's URI is ours
    session = Session(rubric, package_dir, out_dir, side, only)
    lab = labs.lab_module(rubric.lab)
    outcomes = dict(lab.static_checks(session))
    master = Master(os.path.join(out_dir, 'roscore.txt'))
    deliver = deliver or (lambda result: None)
    discard_prepared = lambda: None   # noqa: E731 (what the lab prepared during the build, unused)
    try:
        # The build on a thread of its own: meanwhile the lab prepares its simulators (labs/<lab>.prepare:
        # nothing of the student's runs during the build) and the master comes up.
        with ThreadPoolExecutor(max_workers=1) as pool:
            building = pool.submit(build, session, scratch, build_cache and BuildCache(build_cache), build_jobs)
            try:
                if hasattr(lab, 'prepare'):
                    discard_prepared = lab.prepare(session)
                master.ready()
            finally:
                overlay_env = building.result()
    except BuildFailed as error:
        discard_prepared()
        side.stop_all()
        outcomes['builds'] = Verdict(False, str(error))
        result = results.score(rubric, outcomes, student, error='not run: the package does not build',
                               seconds=time.monotonic() - started)
        deliver(result)
        master.stop()
        return result
    except BaseException:
        discard_prepared()
        master.stop()
        raise
    side.stop_all()
    print('grade_submission: built in %.1f s' % (time.monotonic() - started), flush=True)
    outcomes['builds'] = Verdict(True, 'catkin_make built it')
    # Only the student's side gets the overlay (and the master): the trusted side keeps the course's.
    side.env = dict(overlay_env, ROS_MASTER_URI=master.uri, HOME=side.home,
                    ROS_HOME=side.env['ROS_HOME'], PYTHONDONTWRITEBYTECODE='1', ROSCONSOLE_STDOUT_LINE_BUFFERED='1')
    error = None
    try:
        lost = master.lost()   # a process of the build could reach it
        if lost:
            error = 'not run: %s during the build' % lost
            discard_prepared()
        else:
            session.master = master   # run_each asks it after each run
            outcomes.update(lab.run_checks(session))
        result = results.score(rubric, outcomes, student, error=error, pictures=session.pictures,
                               seconds=time.monotonic() - started)
        result['notes'] = list(session.notes)
        deliver(result)
    finally:
        master.stop()
    return result


def send_folder(folder, stream):
    """The output folder as a tar stream (regular files only) on `stream`."""
    with tarfile.open(fileobj=stream, mode='w|') as archive:
        for name in sorted(os.listdir(folder)):
            path = os.path.join(folder, name)
            if os.path.isfile(path) and not os.path.islink(path):
                archive.add(path, arcname=name, recursive=False)


def main(argv=None):
    parser = argparse.ArgumentParser(description='Grades one submission inside its sandbox.')
    parser.add_argument('--lab', required=True)
    parser.add_argument('--rubric', help='rubric file (default: the lab\'s)')
    parser.add_argument('--package', required=True, help='folder of the student\'s package')
    parser.add_argument('--out', required=True, help='output folder (private to this process with --send)')
    parser.add_argument('--scratch', required=True, help='empty folder for the student\'s side')
    parser.add_argument('--student', required=True)
    parser.add_argument('--student-user', help='run the student\'s side as this user (we are root)')
    parser.add_argument('--only', metavar='ID', help='run only the checks of this criterion (the others: not checked)')
    parser.add_argument('--build-cache', metavar='FOLDER',
                        help='keep the build there for the next session of this lab (the student\'s check)')
    parser.add_argument('--build-jobs', type=int, default=1, metavar='N', help='compilations at once (default: 1)')
    parser.add_argument('--send', action='store_true',
                        help='send the output folder as a tar stream on standard output at the end')
    args = parser.parse_args(argv)
    if args.send:   # standard output carries the result only: what we print goes to standard error
        result_stream = os.fdopen(os.dup(1), 'wb')
        os.dup2(2, 1)
    rubric = rubrics.load(args.rubric or args.lab)
    os.makedirs(args.out, mode=0o700, exist_ok=True)
    os.makedirs(args.scratch, mode=0o1777 if args.student_user else 0o700, exist_ok=True)
    if args.student_user:
        os.chmod(args.scratch, 0o1777)   # the student's side makes its folders there
    os.environ.setdefault('ROS_HOME', os.path.join(args.out + '.ros'))
    os.environ['PYTHONDONTWRITEBYTECODE'] = '1'
    os.environ['ROSCONSOLE_STDOUT_LINE_BUFFERED'] = '1'   # C++ nodes' lines as they print them

    def deliver(result):
        results.write(result, args.out)
        if args.send:
            send_folder(args.out, result_stream)
            result_stream.close()
            sys.stderr.flush()
            # Sent: the sandbox may end now. The master's stop and rospy's own shutdown would cost a
            # second; what is left ends with the container (or, without one, by the grader's mark).
            os._exit(0)
    grade(rubric, args.package, args.out, args.scratch, args.student, args.student_user, args.only, deliver,
          args.build_cache, max(1, args.build_jobs))
    return 0


if __name__ == '__main__':
    sys.exit(main())
