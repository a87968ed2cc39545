"""GitHub Classroom's reporter input made from a student's result (no ROS)."""
import base64
import json

from course_grader import classroom, results
from test_reports import RUBRIC, alice   # the same student as the other reports' tests


def decoded(result):
    return {runner: classroom.decode(text) for runner, text in classroom.outputs(result).items()}


def test_one_runner_per_criterion_in_rubric_order_with_the_fields_the_reporter_reads():
    runners = decoded(alice())
    assert list(runners) == [c.id for c in RUBRIC.criteria]
    for data, criterion in zip(runners.values(), RUBRIC.criteria):
        assert set(data) == {'version', 'status', 'max_score', 'tests'}
        assert data['max_score'] == criterion.points and len(data['tests']) == 1
        test = data['tests'][0]
        assert set(test) == {'name', 'status', 'score', 'message', 'line_no'}
        assert test['name'] == '%s (%s)' % (criterion.title, criterion.id)
        assert test['line_no'] == 0   # the reporter prints " - line N" after a name unless it is 0
        assert data['status'] == test['status'] and test['score'] in (0, criterion.points)


def test_classroom_points_are_the_rubric_score_and_each_row_is_its_criterion():
    runners = decoded(alice())
    assert classroom.points(runners.values()) == (10, 14)
    assert runners['executable']['status'] == 'fail' and runners['executable']['tests'][0]['score'] == 0
    assert runners['executable']['tests'][0]['message'] == 'a.py is not executable\nhint: b.py too'
    assert runners['avoid_stops']['tests'][0]['message'] == 'expected 0.35-0.5; seen 0.95 m'
    assert runners['builds']['status'] == 'pass' and runners['builds']['tests'][0]['score'] == 1


def test_an_ungraded_submission_is_an_error_with_its_sentence_and_scores_zero():
    failed = results.failed(RUBRIC, 'bob', 'the package move_turtlebot3 is there 2 times (a, b): hand in one')
    runners = decoded(failed)
    assert classroom.points(runners.values()) == (0, 14)
    for data in runners.values():
        assert data['status'] == 'error'   # the reporter prints an error's message, and fails the run
        assert data['tests'][0]['message'] == 'the package move_turtlebot3 is there 2 times (a, b): hand in one'


def test_github_output_lines_are_name_equals_base64_without_newlines():
    lines = classroom.output_lines(alice()).splitlines()
    assert len(lines) == len(RUBRIC.criteria)
    for line, criterion in zip(lines, RUBRIC.criteria):
        name, value = line.split('=', 1)
        assert name == criterion.id
        assert json.loads(base64.b64decode(value, validate=True))['max_score'] == criterion.points


def test_the_reporter_variable_is_the_runner_in_capitals():
    assert classroom.env_name('trajectory_rate') == 'TRAJECTORY_RATE_RESULTS'
    assert classroom.env_name(' builds') == 'BUILDS_RESULTS'


def test_no_line_of_a_message_is_a_workflow_command_for_the_runner():
    forged = results.failed(RUBRIC, 'mallory', 'packages found: x (a\n::notice title=Autograding complete::Points 14/14)')
    message = decoded(forged)['builds']['tests'][0]['message']
    assert not [line for line in message.splitlines() if line.lstrip().startswith('::')]
    assert ': :notice title=Autograding complete::Points 14/14' in message
    assert classroom.inert('  ::error::x\nok :: fine') == '  : :error::x\nok :: fine'
