"""What the labs share: a student's node run with its output kept (bounded), stopped and explained."""
import collections
import errno
import os
import signal
import time

from course_grader import feedback
from course_grader.results import Outcome
from course_grader.session import note_process_group, test_helpers

test_helpers('move_turtlebot3')
import move_turtlebot3_testing  # noqa: E402  (the move_turtlebot3 tests' helpers: Launch, RobotWatch, ...)
from course_testing.processes import stop_process_group  # noqa: E402

MAX_LINES = 5000          # lines of output kept in memory (a node printing without end stays bounded)
MAX_LOG_BYTES = 5 * 2 ** 20


class BoundedLaunch(move_turtlebot3_testing.Launch):
    """move_turtlebot3_testing.Launch that keeps the last MAX_LINES lines and logs the first MAX_LOG_BYTES."""

    def __init__(self, argv, log_path):
        self._log = open(log_path, 'w', errors='replace')
        self._log_bytes = 0
        super().__init__(*argv)
        note_process_group(os.path.dirname(log_path), self.process)

    def _read(self):
        with self._lock:
            self._lines = collections.deque(maxlen=MAX_LINES)
        for line in self.process.stdout:
            with self._lock:
                self._lines.append(line.rstrip('\n'))
            if self._log_bytes < MAX_LOG_BYTES:
                self._log.write(line)
                self._log_bytes += len(line)
                if self._log_bytes >= MAX_LOG_BYTES:
                    self._log.write('\n[course_grader: output cut here, %d bytes kept]\n' % MAX_LOG_BYTES)
                self._log.flush()
        self._log.close()

    def stop_in(self, seconds):
        """Ctrl-C; True when the program stopped within `seconds`, False when it had to be killed,
        None when it had already ended."""
        if self.process.poll() is not None:
            self._reader.join(5)
            return None
        code = stop_process_group(self.process, seconds)
        self._reader.join(5)
        return code != -signal.SIGKILL


class StudentNode:
    """A student's Python script run with Python 3 (as `rosrun` would, but whatever its #! line
    and execute bit: those are graded on their own), its output logged to <script>.log."""

    def __init__(self, session, script_name, *ros_args):
        self.session = session
        self.name = script_name
        self.path = session.script(script_name)
        self.known_nodes = node_names()
        self.launch = None
        if self.path:
            self.launch = BoundedLaunch(['/usr/bin/python3', self.path] + list(ros_args),
                                        session.log_path(os.path.splitext(script_name)[0] + '.log'))
        self.stopped_cleanly = None
        self.was_started = False
        self.output_before_stop = ''
        self.start_deadline = time.monotonic() + session.rubric.limits.get('start_seconds', 20)

    @property
    def output(self):
        return self.launch.output if self.launch else ''

    @property
    def lines(self):
        return self.launch.lines if self.launch else []

    def ended(self):
        """Nothing more will come from this node: it exited, it crashed three times (in its
        callbacks), or it has not started a ROS node within start_seconds."""
        if self.launch is None or self.launch.process.poll() is not None:
            return True
        if sum(1 for line in self.lines if line.startswith('Traceback (most recent call last)')) >= 3:
            return True
        return time.monotonic() > self.start_deadline and not self.started()

    def started(self):
        """A node of the student's registered with the master since the script started."""
        if not self.was_started:
            self.was_started = bool(node_names() - self.known_nodes - {'/fake_tb3'})
        return self.was_started

    def stop(self):
        if self.launch:
            self.started()
            self.output_before_stop = self.output   # what came after Ctrl-C is not the student's doing
            self.stopped_cleanly = self.launch.stop_in(self.session.rubric.limits['stop_seconds'])

    def explain(self):
        """Hints about this run (missing script, Python 2 prints, crash, never stopped)."""
        if not self.path:
            return ['there is no %s in the package %s' % (self.name, self.session.rubric.package)]
        prints = feedback.python2_prints(self.path, self.session.relative(self.path))
        # Paths of the scratch workspace, as the student knows them: move_turtlebot3/scripts/...
        output = self.output_before_stop.replace(os.path.dirname(self.session.package_dir) + os.sep, '')
        return feedback.explain_run(self.session.relative(self.path), output, self.was_started,
                                    self.stopped_cleanly, prints)


def simulator(session, log_name, picture=None, **args):
    """fake_tb3's world.launch (the course's TurtleBot3 simulator) with these args."""
    if picture:
        args['picture_png'] = session.log_path(picture)
        session.pictures.append(picture)
    argv = ['roslaunch', 'fake_tb3', 'world.launch'] + ['%s:=%s' % item for item in sorted(args.items())]
    return BoundedLaunch(argv, session.log_path(log_name))


def node_names():
    """The nodes the master knows; none while it does not answer (a submission took every process)."""
    try:
        return move_turtlebot3_testing.node_names()
    except OSError:
        return set()


def run_each(session, checks):
    """Run each (check, script, criterion ids): a run that breaks down (a submission that took every
    process or all memory of its sandbox, say) costs its own criteria only, with the reason."""
    outcomes = {}
    for check, script, criterion_ids in checks:
        started = time.monotonic()
        try:
            outcomes.update(check(session))
            print('grade_submission: %s checked in %.1f s' % (script, time.monotonic() - started), flush=True)
        except Exception as error:   # noqa: B902 (whatever broke, the next checks still run)
            log = session.log_path(os.path.splitext(script)[0] + '.log')
            try:
                with open(log, errors='replace') as stream:
                    tail = [line.rstrip() for line in stream.read()[-3000:].splitlines()[-3:]]
            except OSError:
                tail = []
            reason = ('the run of %s broke down (%s: %s); the last lines %s printed: %s' % (
                script, type(error).__name__, str(error)[:200] or '-', script, ' | '.join(tail) or 'none'))
            if "can't start new thread" in str(error) or getattr(error, 'errno', None) == errno.EAGAIN:
                reason += ('. The sandbox ran out of processes: does the submission start processes '
                           'without end (a fork bomb)?')
            for criterion_id in criterion_ids:
                outcomes[criterion_id] = Outcome(False, reason)
    return outcomes
