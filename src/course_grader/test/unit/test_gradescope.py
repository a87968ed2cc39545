"""Gradescope's results.json made from a student's result (no ROS)."""
import json

from course_grader import gradescope, results
from test_reports import RUBRIC, alice   # the same student as the other reports' tests


def test_one_test_per_criterion_with_the_fields_gradescope_reads():
    data = gradescope.from_result(alice())
    assert data['score'] == 10
    assert data['execution_time'] == 30
    assert len(data['tests']) == len(RUBRIC.criteria)
    for test, criterion in zip(data['tests'], RUBRIC.criteria):
        assert set(test) == {'name', 'number', 'score', 'max_score', 'status', 'output', 'visibility'}
        assert criterion.id in test['name'] and test['max_score'] == criterion.points
        assert test['status'] in ('passed', 'failed') and test['visibility'] == 'visible'
    assert sum(t['score'] for t in data['tests']) == data['score']
    assert sum(t['max_score'] for t in data['tests']) == RUBRIC.max_score


def test_reasons_hints_and_pictures_reach_the_student():
    data = gradescope.from_result(alice())
    executable = next(t for t in data['tests'] if '(executable)' in t['name'])
    assert executable['status'] == 'failed' and executable['score'] == 0
    assert executable['output'] == 'a.py is not executable\nhint: b.py too'
    assert 'trajectory.png' in data['output'] and '10 / 14' in data['output']


def test_an_ungraded_submission_scores_zero_and_says_why(tmp_path):
    failed = results.failed(RUBRIC, 'bob', 'no package named move_turtlebot3')
    gradescope.write(failed, str(tmp_path))
    data = json.loads((tmp_path / 'results.json').read_text(encoding='utf-8'))
    assert data['score'] == 0 and 'no package named move_turtlebot3' in data['output']
    assert all(t['status'] == 'failed' and t['output'] == 'no package named move_turtlebot3' for t in data['tests'])
