"""What the labs share: the record of a lab's table of runs, a student's node run with its output
kept (bounded), stopped and explained, and each run costing its own criteria only."""
import errno
import os
import random
import time
import traceback
from typing import Callable, NamedTuple

from course_checks.robot import left_the_graph, node_names
from course_checks.verdict import Verdict
from course_grader import feedback


class LabRun(NamedTuple):
    """One step of a lab after the build: a row of the lab's table RUNS."""
    name: str          # the script or launch file it runs
    check: Callable    # check(session) -> {criterion id: Verdict}
    criteria: dict     # {criterion id: the rubric settings its check reads} of those it decides (a reading: none)
    kinds: tuple       # what it takes of the wall limit: a wall_limit kind (NODES, READING) for each part
    log: str = None    # the log its check writes: <name without its extension>.log unless given


def criteria_of(static, runs):
    """A lab's CRITERIA, what rubric.check_against gets: {criterion id: settings its check reads} of
    `static` (the criteria decided without a run) and of each of `runs`, in that order."""
    criteria = dict(static)
    for run in runs:
        criteria.update(run.criteria)
    return criteria


def drawn(bounds, either_way=False):
    """A number drawn for this grading between the rubric's [low, high] (rubric.check_drawn), of
    either sign when `either_way`: what the grader sends a node, or does to its robot, that no node
    can know before it comes (a stored printout or a drive by the clock fits no other grading)."""
    draw = random.SystemRandom()
    value = draw.uniform(*bounds)
    return draw.choice((-1, 1)) * value if either_way else value


def will_run(session, runs):
    """The runs of `runs` that the session runs: with session.only, those that decide that
    criterion, and the readings (they decide none: the runs after them use what was read)."""
    return [run for run in runs if not session.only or not run.criteria or session.only in run.criteria]


class StudentNode:
    """A student's Python script run with Python 3 on the student's side (as `rosrun` would, but
    whatever its #! line and execute bit: those are graded on their own), its output logged to
    <script>.log."""

    def __init__(self, session, script_name, *ros_args):
        self.session = session
        self.name = script_name
        self.path = session.script(script_name)
        self.known_nodes = node_names()
        self.launch = None
        if self.path:
            self.launch = session.student(['/usr/bin/python3', self.path] + list(ros_args),
                                          os.path.splitext(script_name)[0] + '.log')
        self.stopped_cleanly = None
        self.exit_before_stop = None   # its exit status when it ended before the grader stopped it
        self.names = set()   # of the ROS nodes it started
        self.output_before_stop = ''
        self.start_deadline = time.monotonic() + session.rubric.limits['start_seconds']

    @property
    def output(self):
        return self.launch.output if self.launch else ''

    @property
    def lines(self):
        return self.launch.lines if self.launch else []

    def ended(self):
        """Nothing more will come from this node: it exited, it crashed three times (in its
        callbacks), or it has not started a ROS node within start_seconds."""
        if self.launch is None or self.launch.ended():
            return True
        if sum(1 for line in self.lines if line.startswith('Traceback (most recent call last)')) >= 3:
            return True
        return time.monotonic() > self.start_deadline and not self.started()

    @property
    def was_started(self):
        return bool(self.names)

    def started(self):
        """A node of the student's registered with the master since the script started."""
        if not self.names:
            self.names = node_names() - self.known_nodes - {'/fake_tb3'}
        return self.was_started

    def left_the_graph(self):
        """The ROS nodes it started are gone from the master (rospy leaves it first on Ctrl-C)."""
        return left_the_graph(self.names)

    def stop(self):
        """Ctrl-C; a node that started a ROS node has stopped once that node left the graph (rospy's
        exit after that, 0.6 s, is not waited for); one that started none, once it ended."""
        if self.launch:
            self.started()
            self.exit_before_stop = self.launch.process.poll()
            self.output_before_stop = self.output   # what came after Ctrl-C is not the student's doing
            self.stopped_cleanly = self.launch.stop(self.session.rubric.limits['stop_seconds'],
                                                    self.left_the_graph if self.names else None)

    def explain(self):
        """Hints about this run (missing script, Python 2 prints, crash, never stopped)."""
        if not self.path:
            return ['there is no %s in the package %s' % (self.name, self.session.rubric.package)]
        prints = feedback.python2_prints(self.path, self.session.relative(self.path))
        # Paths of the scratch workspace, as the student knows them: move_turtlebot3/scripts/...
        output = self.output_before_stop.replace(os.path.dirname(self.session.package_dir) + os.sep, '')
        return feedback.explain_run(self.session.relative(self.path), output, self.was_started,
                                    self.stopped_cleanly, prints, self.path, self.session.rubric.package,
                                    self.exit_before_stop)


def run_each(session, runs, **given):
    """Run each of `runs` (LabRun; its check gets the session and `given`): a run that breaks down
    (a submission that took every process or all memory of its sandbox, say) costs its own criteria
    only, with the reason; a run after which session.master (grading_session.Master) is lost (not
    the one the session started, or the grader's own node shut down) costs its criteria and those
    of every run after it. With session.only, only the runs that judge that criterion (will_run)."""
    outcomes = {}
    master_lost = None   # (what became of the session's master or the grader's node, during which run)
    for run in will_run(session, runs):
        if master_lost:
            outcomes.update({criterion_id: Verdict(False, 'not run: %s during the run of %s' % master_lost)
                             for criterion_id in run.criteria})
            continue
        started = time.monotonic()
        try:
            outcomes.update(run.check(session, **given))
            if run.criteria:   # the runs, as the student's check lists them (a reading is part of those after it)
                print('grade_submission: %s checked in %.1f s' % (run.name, time.monotonic() - started), flush=True)
        except Exception as error:   # noqa: B902 (whatever broke, the next checks still run)
            # For the teacher's log (grader.txt): where in the grader's own code it broke, which may
            # be the grader's fault. File names, lines and functions only: nothing the student wrote.
            print('grade_submission: %s broke down (%s) at %s' % (run.name, type(error).__name__, ' < '.join(
                '%s:%d %s' % (os.path.basename(frame.filename), frame.lineno, frame.name)
                for frame in reversed(traceback.extract_tb(error.__traceback__)[-4:]))), flush=True)
            tail = feedback.log_tail(session.log_path(run.log or os.path.splitext(run.name)[0] + '.log'),
                                     3).splitlines()
            reason = ('the run of %s broke down (%s: %s); the last lines %s printed: %s' % (
                run.name, type(error).__name__, str(error)[:200] or '-', run.name, ' | '.join(tail) or 'none'))
            if "can't start new thread" in str(error) or getattr(error, 'errno', None) == errno.EAGAIN:
                reason += ('. The sandbox ran out of processes: does the submission start processes '
                           'without end (a fork bomb)?')
            for criterion_id in run.criteria:
                outcomes[criterion_id] = Verdict(False, reason)
        session.student_side.stop_all()   # nothing of this run's lives into the next
        lost = session.master.lost() if getattr(session, 'master', None) else None
        if lost:   # what the master answered may be lies, what the grader's node sent may not have gone
            master_lost = (lost, run.name)
            reason = ('not judged: %s during the run of %s (a node can do that through the ROS APIs): '
                      'what the grader saw of that run cannot be trusted' % master_lost)
            outcomes.update({criterion_id: Verdict(False, reason) for criterion_id in run.criteria})
    return outcomes


def faked(criterion_ids, impostors, owner):
    """Failing verdicts for criteria judged on topics another node than the simulator published on."""
    named = '; '.join('%s by %s' % (topic, ', '.join(nodes)) for topic, nodes in sorted(impostors.items()))
    reason = ('not judged: messages on topics only %s publishes came from other nodes (%s): a node of the '
              'submission published what the simulator owns' % (owner, named))
    return {criterion_id: Verdict(False, reason) for criterion_id in criterion_ids}
