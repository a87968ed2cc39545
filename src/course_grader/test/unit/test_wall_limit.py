"""The wall limit of a grading session: every step of the lab at its limit, and a margin."""
import os
import re

import pytest

from course_grader import labs, rubric as rubrics, wall_limit
from course_grader.labs import wall_limit_of
from course_grader.wall_limit import NODES, READING

ROOT = os.path.join(os.path.dirname(__file__), '..', '..', '..', '..')


def kinds(lab):
    """What each step of the lab's table takes of the wall limit, in order."""
    return [kind for run in labs.lab_module(lab).RUNS for kind in run.kinds]


def steps_at_their_limits(rubric):
    """The build, the overlay's environment read, and each run of the lab, each at its limit."""
    limits = rubric.limits
    runs = kinds(rubric.lab)
    return (limits['build_seconds'] + wall_limit.STEP_SECONDS + runs.count(READING) * wall_limit.STEP_SECONDS
            + runs.count(NODES) * (limits['start_seconds'] + limits['run_seconds'] + limits['stop_seconds']))


@pytest.mark.parametrize('lab, seconds', [('move_turtlebot3', 630), ('my_turtle', 670), ('ros_exercises', 1010)])
def test_the_limit_covers_every_step_at_its_limit_with_the_margins_stated(lab, seconds):
    rubric = rubrics.load(lab)
    assert wall_limit_of(rubric) == seconds
    assert seconds - steps_at_their_limits(rubric) == (wall_limit.SESSION_MARGIN
                                                       + kinds(lab).count(NODES) * wall_limit.RUN_MARGIN)


def test_each_limit_counts_once_for_each_step_that_has_it():
    limits = dict.fromkeys(rubrics.LIMITS, 0)
    runs = (READING, NODES, NODES)
    base = wall_limit.seconds(limits, runs)
    assert base == wall_limit.SESSION_MARGIN + 2 * wall_limit.STEP_SECONDS + 2 * wall_limit.RUN_MARGIN
    for name, uses in (('build_seconds', 1), ('start_seconds', 2), ('run_seconds', 2), ('stop_seconds', 2)):
        assert wall_limit.seconds(dict(limits, **{name: 10}), runs) == base + 10 * uses


def test_classroom_and_the_docs_give_more_time_than_any_lab_takes():
    longest = max(wall_limit_of(rubrics.load(lab)) for lab in rubrics.labs())
    with open(os.path.join(ROOT, 'src', 'course_grader', 'platforms', 'classroom.yml.in')) as stream:
        job_minutes = int(re.search(r'timeout-minutes: (\d+)', stream.read()).group(1))
    assert longest < job_minutes * 60
    with open(os.path.join(ROOT, 'docs', 'grading.md')) as stream:
        docs = ' '.join(stream.read().split())
    gradescope_minutes = int(re.search(r'a timeout of (\d+) minutes', docs).group(1))
    assert longest < gradescope_minutes * 60
    for lab in rubrics.labs():
        assert '%d s for `%s`' % (wall_limit_of(rubrics.load(lab)), lab) in docs
