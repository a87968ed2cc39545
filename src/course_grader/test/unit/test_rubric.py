"""Rubric files: the shipped ones load, a teacher's mistakes are named."""
import pytest

from course_grader import rubric


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
