"""The grading of one submission, inside its sandbox (a container, or a process group of its own):
build the student's package in a scratch catkin workspace overlaid on the course workspace, start
a master, run the lab's checks, write result.json, logs and pictures into the output folder.

This is the only part of the grader that runs next to the student's code; the host reads what it
writes as untrusted (results.read)."""
import argparse
import importlib
import os
import shutil
import subprocess
import sys
import time

from course_grader import feedback, results, rubric as rubrics
from course_grader.results import Outcome

COURSE_SRC = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..'))


def test_helpers(package):
    """The test folder of the course's own package, so that the grader runs the checks of the
    project's tests (a student's package of the same name shadows the course's on ROS paths)."""
    folder = os.path.join(COURSE_SRC, package, 'test')
    if folder not in sys.path:
        sys.path.insert(0, folder)
    return folder


PROCESS_GROUPS = 'process_groups.txt'   # in the output folder: every group the session started


def note_process_group(out_dir, process):
    """Remember a process group started in a session of its own, so that the host can kill what is
    left of it when it runs the session without a container (where nothing else would)."""
    with open(os.path.join(out_dir, PROCESS_GROUPS), 'a') as stream:
        stream.write('%d\n' % process.pid)


class Deadline:
    def __init__(self, seconds):
        self.end = time.monotonic() + seconds

    def left(self, at_least=0.5):
        return max(at_least, self.end - time.monotonic())


class Session:
    """What the lab's checks need: the package's folder, the rubric, the output folder, logs."""

    def __init__(self, rubric, package_dir, out_dir):
        self.rubric = rubric
        self.package_dir = package_dir
        self.out_dir = out_dir
        self.pictures = []

    def script(self, name):
        """Path of a student's script by file name (scripts/ first), or None."""
        from course_grader.submission import find_file
        hits = find_file(self.package_dir, name)
        return os.path.join(self.package_dir, hits[0]) if hits else None

    def relative(self, path):
        return os.path.relpath(path, os.path.dirname(self.package_dir))

    def log_path(self, name):
        return os.path.join(self.out_dir, name)


def run_logged(argv, log_path, timeout, cwd=None, env=None):
    """Run a command in its own process group, output to log_path (at most 20 MB); on timeout
    kill the group. Returns the exit code, or None when the time limit was reached."""
    from course_testing.processes import stop_process_group
    with open(log_path, 'wb') as log:
        process = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, cwd=cwd,
                                   env=env, start_new_session=True)
        note_process_group(os.path.dirname(log_path), process)
        deadline = time.monotonic() + timeout
        written = 0
        import selectors
        selector = selectors.DefaultSelector()
        selector.register(process.stdout, selectors.EVENT_READ)
        while True:
            if time.monotonic() > deadline:
                stop_process_group(process, 5)
                return None
            if selector.select(timeout=0.5):
                chunk = os.read(process.stdout.fileno(), 65536)
                if not chunk:
                    break
                if written < 20 * 2 ** 20:
                    log.write(chunk)
                    written += len(chunk)
        return process.wait(max(1.0, deadline - time.monotonic()))


def build(session, scratch):
    """catkin_make of the student's package in scratch/ (overlay of the sourced course workspace).
    Returns the environment of the built overlay, or raises BuildFailed."""
    src = os.path.join(scratch, 'src')
    os.makedirs(src, exist_ok=True)
    package = os.path.join(src, session.rubric.package)
    shutil.copytree(session.package_dir, package, symlinks=True)
    session.package_dir = package
    log = session.log_path('build.log')
    code = run_logged(['catkin_make', '--directory', scratch, '-DPYTHON_EXECUTABLE=/usr/bin/python3',
                       '-DCMAKE_BUILD_TYPE=Release', '-j1'], log, session.rubric.limits['build_seconds'])
    if code != 0:
        with open(log, errors='replace') as stream:
            text = stream.read()
        if code is None:
            raise BuildFailed('catkin_make did not finish within %d s' % session.rubric.limits['build_seconds'])
        raise BuildFailed(feedback.first_compiler_error(text) or 'catkin_make failed (exit %d): see build.log' % code)
    env_text = subprocess.run(['bash', '-c', 'source "$1/devel/setup.bash" && env -0', 'env', scratch],
                              capture_output=True, check=True, timeout=60).stdout
    return dict(item.split('=', 1) for item in env_text.decode().split('\0') if '=' in item)


class BuildFailed(Exception):
    pass


class Master:
    """A roscore of our own on a free port (and the grader's own rospy node on it)."""

    def __init__(self, log_path):
        from course_testing.processes import free_port
        import rosgraph
        self.port = free_port()
        os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % self.port
        self.log = open(log_path, 'wb')
        self.process = subprocess.Popen(['roscore', '-p', str(self.port)], stdout=self.log,
                                        stderr=subprocess.STDOUT, start_new_session=True)
        note_process_group(os.path.dirname(log_path), self.process)
        deadline = time.monotonic() + 60
        master = rosgraph.Master('/course_grader')
        while True:
            try:
                master.getParam('/run_id')
                break
            except Exception:
                if time.monotonic() > deadline or self.process.poll() is not None:
                    raise RuntimeError('roscore did not start on port %d' % self.port)
                time.sleep(0.1)
        master.setParam('/use_sim_time', False)
        import rospy
        rospy.init_node('course_grader', disable_signals=True)

    def stop(self):
        from course_testing.processes import stop_process_group
        import rospy
        rospy.signal_shutdown('graded')
        stop_process_group(self.process, 15)
        self.log.close()


def grade(rubric, package_dir, out_dir, scratch, student):
    started = time.monotonic()
    session = Session(rubric, package_dir, out_dir)
    lab = importlib.import_module('course_grader.labs.' + rubric.lab)
    outcomes = {}
    early = lab.static_checks(session) if hasattr(lab, 'static_checks') else {}
    try:
        overlay_env = build(session, scratch)
    except BuildFailed as error:
        outcomes.update(early)
        outcomes['builds'] = Outcome(False, str(error))
        return results.score(rubric, outcomes, student, error='not run: the package does not build',
                             seconds=time.monotonic() - started)
    print('grade_submission: built in %.1f s' % (time.monotonic() - started), flush=True)
    outcomes['builds'] = Outcome(True, 'catkin_make built it')
    outcomes.update(early)
    os.environ.update(overlay_env)
    master = Master(os.path.join(out_dir, 'roscore.txt'))
    try:
        outcomes.update(lab.run_checks(session))
    finally:
        master.stop()
    return results.score(rubric, outcomes, student, pictures=session.pictures,
                         seconds=time.monotonic() - started)


def main(argv=None):
    parser = argparse.ArgumentParser(description='Grades one submission inside its sandbox.')
    parser.add_argument('--lab', required=True)
    parser.add_argument('--rubric', help='rubric file (default: the lab\'s)')
    parser.add_argument('--package', required=True, help='folder of the student\'s package')
    parser.add_argument('--out', required=True)
    parser.add_argument('--scratch', required=True, help='empty folder for the scratch workspace')
    parser.add_argument('--student', required=True)
    args = parser.parse_args(argv)
    rubric = rubrics.load(args.rubric or args.lab)
    os.environ.setdefault('ROS_HOME', os.path.join(args.scratch, 'ros_home'))
    os.environ['PYTHONDONTWRITEBYTECODE'] = '1'
    os.environ['ROSCONSOLE_STDOUT_LINE_BUFFERED'] = '1'   # C++ nodes' lines as they print them
    result = grade(rubric, args.package, args.out, args.scratch, args.student)
    results.write(result, args.out)
    return 0
