"""Rubric files: the shipped ones load, a teacher's mistakes are named."""
import random

import pytest
import yaml

from course_grader import rubric
from course_grader.labs import common, lab_module


def test_every_shipped_rubric_loads_with_points():
    assert 'move_turtlebot3' in rubric.labs()
    for lab in rubric.labs():
        loaded = rubric.load(lab)
        assert loaded.lab == lab and loaded.max_score > 0
        assert loaded.limits['build_seconds'] > 0 and loaded.limits['run_seconds'] > 0


def test_move_turtlebot3_criteria_and_thresholds():
    loaded = rubric.load('move_turtlebot3')
    assert [c.id for c in loaded.criteria] == ['builds', 'executable', 'trajectory_rate', 'trajectory_circle',
                                               'laser_data', 'avoid_stops', 'avoid_stays']
    assert loaded.max_score == 14
    assert loaded.criterion('avoid_stops')['front_max'] == 0.5
    assert '#! line' in loaded.criterion('executable').title


@pytest.mark.parametrize('text, message', [
    ('[1, 2]', 'must be a mapping'),
    ('lab: x\npackage: x\n', "no 'criteria'"),
    ('lab: x\npackage: x\ncriteria: []\n', 'non-empty list'),
    ('lab: x\npackage: x\ncriteria: [{id: a, title: t}]\n', "no 'points'"),
    ('lab: x\npackage: x\ncriteria: [{id: a, title: t, points: -1}]\n', 'must be a number >= 0'),
    ('lab: x\npackage: x\ncriteria: [{id: a, title: t, points: 1}, {id: a, title: u, points: 2}]\n',
     'used twice: a'),
    ('lab: [x\n', 'not valid YAML'),
])
def test_bad_rubrics_are_named(tmp_path, text, message):
    path = tmp_path / 'x.yaml'
    path.write_text(text)
    with pytest.raises(rubric.RubricError, match=message):
        rubric.load(str(path))


def test_unknown_lab_lists_the_labs():
    with pytest.raises(rubric.RubricError, match='no rubric for lab .nope. .the labs are: .*move_turtlebot3'):
        rubric.load('nope')


LAB = 'lab: move_turtlebot3\npackage: move_turtlebot3\n'
LIMITS = 'limits: {build_seconds: 1, run_seconds: 1, start_seconds: 1, stop_seconds: 1}\n'


def shipped_with(path, change):
    """The shipped move_turtlebot3 rubric, its criteria changed by change(list of mappings), at path."""
    data = yaml.safe_load(open(rubric.load('move_turtlebot3').path))
    change(data['criteria'])
    path.write_text(yaml.safe_dump(data))
    return str(path)


def criterion_of(criteria, criterion_id):
    return next(c for c in criteria if c['id'] == criterion_id)


@pytest.mark.parametrize('change, message', [
    (lambda criteria: criteria.append({'id': 'trajectory_speed', 'title': 't', 'points': 1}),
     r'criterion trajectory_speed is not one that course_grader.labs.move_turtlebot3 checks '
     r'\(it checks: builds, executable, trajectory_rate, .*avoid_stays\)'),
    (lambda criteria: criteria.remove(criterion_of(criteria, 'laser_data')),
     r'criterion laser_data of course_grader.labs.move_turtlebot3 is missing from the rubric'),
    (lambda criteria: criterion_of(criteria, 'avoid_stops').pop('front_max'),
     r'criterion avoid_stops has no front_max \(its check in course_grader.labs.move_turtlebot3 reads them\)'),
    (lambda criteria: criterion_of(criteria, 'avoid_stays').update(max_crep=0.2),
     r'criterion avoid_stays gives max_crep, which its check in course_grader.labs.move_turtlebot3 does not read '
     r'\(it reads: .*max_creep'),
    (lambda criteria: criterion_of(criteria, 'avoid_stops').update(put_back_after=5.0),
     r'put_back_after of criterion avoid_stops must be \[low, high\], two numbers with 0 < low <= high \(the grader '
     r'draws one between them at each grading\), not 5.0'),
    (lambda criteria: criterion_of(criteria, 'avoid_stops').update(put_back_distance=[1.5, 0.3]),
     r'put_back_distance of criterion avoid_stops must be \[low, high\].*not \[1.5, 0.3\]'),
    (lambda criteria: criterion_of(criteria, 'avoid_stops').update(put_back_distance=[0, '1']),
     r'put_back_distance of criterion avoid_stops must be \[low, high\].*not \[0, .1.\]'),
])
def test_a_rubric_that_does_not_fit_its_lab_is_refused_naming_what(tmp_path, change, message):
    with pytest.raises(rubric.RubricError, match=message):
        rubric.load(shipped_with(tmp_path / 'x.yaml', change))


@pytest.mark.parametrize('limits', ['', 'limits: {build_seconds: 1, run_seconds: 1, start_seconds: 1}\n',
                                    'limits: [1, 2]\n'])
def test_missing_limits_are_named(tmp_path, limits):
    path = tmp_path / 'x.yaml'
    path.write_text(LAB + limits + 'criteria: [{id: builds, title: t, points: 1}]\n')
    with pytest.raises(rubric.RubricError, match='limits must give build_seconds, run_seconds, start_seconds, '
                                                 'stop_seconds'):
        rubric.load(str(path))


def test_a_lab_the_grader_does_not_have_is_named(tmp_path):
    path = tmp_path / 'x.yaml'
    path.write_text('lab: nope\npackage: x\n' + LIMITS + 'criteria: [{id: builds, title: t, points: 1}]\n')
    with pytest.raises(rubric.RubricError, match="lab 'nope' is none of the grader's .move_turtlebot3, my_turtle"):
        rubric.load(str(path))


def test_what_the_grader_draws_stays_within_the_rubrics_bounds_either_way_round(monkeypatch):
    # Seeded here: in a grading each draw comes from the system's randomness.
    seeds = iter(range(40))
    monkeypatch.setattr(common.random, 'SystemRandom', lambda: random.Random(next(seeds)))
    speeds = [common.drawn([0.3, 0.8]) for _ in range(20)]
    turns = [common.drawn([0.3, 0.8], either_way=True) for _ in range(20)]
    assert all(0.3 <= speed <= 0.8 for speed in speeds) and len(set(speeds)) == 20
    assert all(0.3 <= abs(turn) <= 0.8 for turn in turns) and min(turns) < 0 < max(turns)
    # Each lab's drawn settings, in the shipped rubrics, are such bounds.
    for lab in rubric.labs():
        for criterion_id, key in getattr(lab_module(lab), 'DRAWN', ()):
            low, high = rubric.load(lab).criterion(criterion_id)[key]
            assert 0 < low <= high, (lab, criterion_id, key)
