"""The runs of a lab, each costing its own criteria only; with --only, the runs of that criterion only."""
import re
import types

from course_checks.verdict import Verdict
from course_grader.labs.common import LabRun, run_each, will_run
from course_grader.wall_limit import NODES, READING


def session(only=None, folder='/nonexistent', ran=None):
    """A session whose student's side notes in `ran` when all its processes are stopped."""
    stop_all = (lambda: ran.append('stopped')) if ran is not None else (lambda: None)
    return types.SimpleNamespace(only=only, log_path=lambda name: '%s/%s' % (folder, name),
                                 student_side=types.SimpleNamespace(stop_all=stop_all))


def runs(ran):
    def first(_):
        ran.append('first')
        return {'a': Verdict(True, 'seen a'), 'b': Verdict(True, 'seen b')}

    def second(_):
        ran.append('second')
        return {'c': Verdict(True, 'seen c')}
    return [LabRun('first.launch', first, {'a': (), 'b': ('rate',)}, (NODES,)),
            LabRun('second.py', second, {'c': ()}, (NODES,))]


def reading(ran):
    def read(_):
        ran.append('read')
        return {}
    return LabRun('all.launch', read, {}, (READING,))


def test_every_run_without_only():
    ran = []
    assert sorted(run_each(session(), runs(ran))) == ['a', 'b', 'c']
    assert ran == ['first', 'second']


def test_every_process_of_the_students_side_is_stopped_after_each_run():
    ran = []
    run_each(session(ran=ran), runs(ran))
    assert ran == ['first', 'stopped', 'second', 'stopped']


def test_only_runs_the_run_that_judges_that_criterion():
    ran = []
    assert sorted(run_each(session(only='c'), runs(ran))) == ['c']
    assert ran == ['second']


def test_only_a_criterion_of_no_run_runs_none():   # builds: the build is all there is to check
    ran = []
    assert run_each(session(only='builds'), runs(ran)) == {}
    assert ran == []


def reported(capsys):
    """The runs the session reported as checked (what the student's check lists)."""
    return re.findall(r'^grade_submission: (\S+) checked in \d+\.\d s$', capsys.readouterr().out, re.M)


def test_a_reading_runs_whatever_the_criterion_and_is_not_reported_as_a_run(capsys):
    ran = []
    assert sorted(run_each(session(only='c'), [reading(ran)] + runs(ran))) == ['c']
    assert ran == ['read', 'second']
    assert reported(capsys) == ['second.py']
    run_each(session(), [reading(ran)] + runs(ran))
    assert reported(capsys) == ['first.launch', 'second.py']


def test_the_runs_that_will_run_are_those_run_each_runs():   # move_turtlebot3 prepares their simulators
    ran = []
    table = [reading(ran)] + runs(ran)
    assert [run.name for run in will_run(session(only='b'), table)] == ['all.launch', 'first.launch']
    assert will_run(session(), table) == table


def test_each_check_gets_what_run_each_is_given():
    given = []
    run_each(session(), [LabRun('x.py', lambda _, simulators: given.append(simulators) or {}, {'x': ()}, (NODES,))],
             simulators='the simulators')
    assert given == ['the simulators']


def test_a_run_that_breaks_down_costs_its_own_criteria(tmp_path, capsys):
    def broken(_):
        raise RuntimeError("can't start new thread")
    (tmp_path / 'first.log').write_text('starting\nforking\n')
    table = [LabRun('first.launch', broken, {'a': (), 'b': ()}, (NODES,))] + runs([])[1:]
    outcomes = run_each(session(folder=str(tmp_path)), table)
    # The teacher's log says where in the grader's code it broke (the innermost frame first).
    logged = re.findall(r'^grade_submission: first.launch broke down \(RuntimeError\) at (.*)$',
                        capsys.readouterr().out, re.M)
    assert len(logged) == 1 and re.fullmatch(r'test_run_each\.py:\d+ broken < common\.py:\d+ run_each', logged[0]), logged
    assert outcomes['c'].passed
    assert not outcomes['a'].passed and outcomes['a'].reason == outcomes['b'].reason
    assert outcomes['a'].reason.startswith("the run of first.launch broke down (RuntimeError: can't start new thread); "
                                           "the last lines first.launch printed: starting | forking")
    assert 'The sandbox ran out of processes' in outcomes['a'].reason


class LostMaster:
    """A session's master (grading_session.Master) that is lost once `after` has run."""

    def __init__(self, ran, after):
        self.ran, self.after = ran, after

    def lost(self):
        return 'the ROS master stopped' if self.after in self.ran else None


def test_a_run_after_which_the_master_is_not_ours_costs_its_criteria_and_those_of_every_run_after():
    ran = []
    lost_session = session(ran=ran)
    lost_session.master = LostMaster(ran, 'first')
    outcomes = run_each(lost_session, runs(ran))
    assert ran == ['first', 'stopped']   # the second is not run: its master would not be ours
    said = {criterion: (verdict.passed, verdict.reason) for criterion, verdict in outcomes.items()}
    judged = ('not judged: the ROS master stopped during the run of first.launch (a node can do that through the '
              'ROS APIs): what the grader saw of that run cannot be trusted')
    assert said == {'a': (False, judged), 'b': (False, judged),
                    'c': (False, 'not run: the ROS master stopped during the run of first.launch')}


def test_a_master_lost_in_the_last_run_costs_that_run_only():
    ran = []
    lost_session = session(ran=ran)
    lost_session.master = LostMaster(ran, 'second')
    outcomes = run_each(lost_session, runs(ran))
    assert outcomes['a'].passed and outcomes['b'].passed
    assert outcomes['c'].reason.startswith('not judged: the ROS master stopped during the run of second.py')
