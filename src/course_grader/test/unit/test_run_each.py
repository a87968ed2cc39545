"""The runs of a lab, each costing its own criteria only; with --only, the runs of that criterion only."""
import types

from course_checks.verdict import Verdict
from course_grader.labs.common import run_each


def session(only=None, folder='/nonexistent', ran=None):
    """A session whose student's side notes in `ran` when all its processes are stopped."""
    stop_all = (lambda: ran.append('stopped')) if ran is not None else (lambda: None)
    return types.SimpleNamespace(only=only, log_path=lambda name: '%s/%s' % (folder, name),
                                 student_side=types.SimpleNamespace(stop_all=stop_all))


def checks(ran):
    def first(_):
        ran.append('first')
        return {'a': Verdict(True, 'seen a'), 'b': Verdict(True, 'seen b')}

    def second(_):
        ran.append('second')
        return {'c': Verdict(True, 'seen c')}
    return [(first, 'first.launch', ['a', 'b']), (second, 'second.py', ['c'])]


def test_every_run_without_only():
    ran = []
    assert sorted(run_each(session(), checks(ran))) == ['a', 'b', 'c']
    assert ran == ['first', 'second']


def test_every_process_of_the_students_side_is_stopped_after_each_run():
    ran = []
    run_each(session(ran=ran), checks(ran))
    assert ran == ['first', 'stopped', 'second', 'stopped']


def test_only_runs_the_run_that_judges_that_criterion():
    ran = []
    assert sorted(run_each(session(only='c'), checks(ran))) == ['c']
    assert ran == ['second']


def test_only_a_criterion_of_no_run_runs_none():   # builds: the build is all there is to check
    ran = []
    assert run_each(session(only='builds'), checks(ran)) == {}
    assert ran == []


def test_a_run_that_breaks_down_costs_its_own_criteria(tmp_path):
    def broken(_):
        raise RuntimeError("can't start new thread")
    (tmp_path / 'first.log').write_text('starting\nforking\n')
    outcomes = run_each(session(folder=str(tmp_path)), [(broken, 'first.launch', ['a', 'b'])] + checks([])[1:])
    assert outcomes['c'].passed
    assert not outcomes['a'].passed and outcomes['a'].reason == outcomes['b'].reason
    assert outcomes['a'].reason.startswith("the run of first.launch broke down (RuntimeError: can't start new thread); "
                                           "the last lines first.launch printed: starting | forking")
    assert 'The sandbox ran out of processes' in outcomes['a'].reason
