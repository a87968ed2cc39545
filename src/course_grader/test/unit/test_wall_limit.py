"""The wall limit of a grading session: every step of the lab at its limit, and a margin."""
import os
import re
import types

import pytest

from course_grader import labs, rubric as rubrics, wall_limit
from course_grader.wall_limit import NODES, READING

ROOT = os.path.join(os.path.dirname(__file__), '..', '..', '..', '..')


def steps_at_their_limits(rubric):
    """The build, the overlay's environment read, and each run of the lab, each at its limit."""
    limits = rubric.limits
    runs = wall_limit.RUNS[rubric.lab]
    return (limits['build_seconds'] + wall_limit.STEP_SECONDS + runs.count(READING) * wall_limit.STEP_SECONDS
            + runs.count(NODES) * (limits['start_seconds'] + limits['run_seconds'] + limits['stop_seconds']))


def runs_of(lab, monkeypatch):
    """What the lab's run_checks hands to run_each (a run each), and how many times it reads the
    launch files at once beforehand, as (runs, readings)."""
    module = labs.lab_module(lab)
    handed, readings = [], []
    monkeypatch.setattr(module, 'run_each', lambda session, checks: handed.extend(checks) or {})
    if hasattr(module, 'describe_launches'):
        monkeypatch.setattr(module, 'describe_launches', lambda session, launches: readings.append(launches))
    module.run_checks(types.SimpleNamespace(rubric=rubrics.load(lab), only=None))
    return handed, readings


@pytest.mark.parametrize('lab', rubrics.labs())
def test_the_table_has_the_runs_each_lab_does(lab, monkeypatch):
    handed, readings = runs_of(lab, monkeypatch)
    runs = wall_limit.RUNS[lab]
    # my_turtle's one run reads its launch file itself and may start the node again by rosrun.
    assert runs.count(NODES) == len(handed) + (lab == 'my_turtle')
    assert runs.count(READING) == len(readings) + (lab == 'my_turtle')


@pytest.mark.parametrize('lab, seconds', [('move_turtlebot3', 630), ('my_turtle', 670), ('ros_exercises', 930)])
def test_the_limit_covers_every_step_at_its_limit_with_the_margins_stated(lab, seconds):
    rubric = rubrics.load(lab)
    runs = wall_limit.RUNS[lab]
    assert wall_limit.of_rubric(rubric) == seconds
    assert seconds - steps_at_their_limits(rubric) == (wall_limit.SESSION_MARGIN
                                                       + runs.count(NODES) * wall_limit.RUN_MARGIN)


def test_each_limit_counts_once_for_each_step_that_has_it():
    limits = dict.fromkeys(rubrics.LIMITS, 0)
    runs = (READING, NODES, NODES)
    base = wall_limit.seconds(limits, runs)
    assert base == wall_limit.SESSION_MARGIN + 2 * wall_limit.STEP_SECONDS + 2 * wall_limit.RUN_MARGIN
    for name, uses in (('build_seconds', 1), ('start_seconds', 2), ('run_seconds', 2), ('stop_seconds', 2)):
        assert wall_limit.seconds(dict(limits, **{name: 10}), runs) == base + 10 * uses


def test_classroom_and_the_docs_give_more_time_than_any_lab_takes():
    longest = max(wall_limit.of_rubric(rubrics.load(lab)) for lab in rubrics.labs())
    with open(os.path.join(ROOT, 'src', 'course_grader', 'platforms', 'classroom.yml.in')) as stream:
        job_minutes = int(re.search(r'timeout-minutes: (\d+)', stream.read()).group(1))
    assert longest < job_minutes * 60
    with open(os.path.join(ROOT, 'docs', 'grading.md')) as stream:
        docs = ' '.join(stream.read().split())
    gradescope_minutes = int(re.search(r'a timeout of (\d+) minutes', docs).group(1))
    assert longest < gradescope_minutes * 60
    for lab in rubrics.labs():
        assert '%d s for `%s`' % (wall_limit.of_rubric(rubrics.load(lab)), lab) in docs
