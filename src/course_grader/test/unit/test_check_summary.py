"""What the check leaves for the browser view (check.json, course_web.last_check): the criteria as
the check prints them, a hidden one without its points, reason or hints, until its time."""
import json

from course_grader import check
from test_visibility import AFTER, BEFORE, DUE, hidden_alice as hidden_alice_of


def hidden_alice(tmp_path):
    """test_visibility's alice, in the folder the grader gives her."""
    return dict(hidden_alice_of(tmp_path), folder='alice')


def test_a_hidden_criterion_is_its_title_and_why_it_is_hidden(tmp_path):
    result = hidden_alice(tmp_path)
    summary = check.summary(result, 'move_turtlebot3', '/home/alice/catkin_ws/src/move_turtlebot3',
                            [{'run': 'trajectory'}], 'total 10 / 10, 2 criteria hidden (not counted) (9 s)',
                            due=DUE, now=BEFORE)
    shown = {c['id']: c for c in summary['criteria']}
    assert [c['id'] for c in summary['criteria']] == [c['id'] for c in result['criteria']]
    stops = next(c for c in result['criteria'] if c['id'] == 'avoid_stops')
    assert shown['avoid_stops'] == {'id': 'avoid_stops', 'title': stops['title'],
                                    'hidden': 'hidden until the teacher publishes it'}
    assert shown['executable']['hidden'] == 'hidden until the deadline has passed'
    for criterion in result['criteria']:
        if criterion['id'] not in ('avoid_stops', 'executable'):
            assert shown[criterion['id']] == {key: criterion[key] for key in (
                'id', 'title', 'passed', 'points', 'max_points', 'reason', 'hints')}
    assert stops['reason'] and stops['reason'] not in json.dumps(summary)
    assert (summary['total'], summary['runs'], summary['folder'], summary['when']) == (
        'total 10 / 10, 2 criteria hidden (not counted) (9 s)', [{'run': 'trajectory'}], 'alice',
        BEFORE.astimezone().strftime('%Y-%m-%d %H:%M:%S'))


def test_after_the_deadline_an_after_due_date_criterion_is_shown(tmp_path):
    result = hidden_alice(tmp_path)
    shown = {c['id']: c for c in check.summary(result, 'move_turtlebot3', 'p', [], 't', due=DUE, now=AFTER)['criteria']}
    assert shown['executable']['points'] == 0 and 'hidden' not in shown['executable']
    assert 'hidden' in shown['avoid_stops']


def test_with_only_one_criterion_the_summary_has_only_it(tmp_path):
    result = hidden_alice(tmp_path)
    summary = check.summary(result, 'move_turtlebot3', 'p', [], 't', only='builds')
    assert [c['id'] for c in summary['criteria']] == ['builds']
