"""What the student sees of each criterion (the rubric's `visibility`): the check and a Classroom
run show a hidden one as a line without points, reason or hints; Gradescope reads it per test; the
teacher's reports show everything."""
import datetime
import io

import pytest
import yaml

from course_grader import check, classroom, gradescope, platform_grading, reports, results, rubric as rubrics
from test_reports import RUBRIC, alice

UTC = datetime.timezone.utc
DUE = datetime.datetime(2026, 12, 2, tzinfo=UTC)
BEFORE, AFTER = DUE - datetime.timedelta(seconds=1), DUE


def rubric_with(tmp_path, **visibility):
    with open(RUBRIC.path) as stream:
        data = yaml.safe_load(stream)
    for criterion in data['criteria']:
        if criterion['id'] in visibility:
            criterion['visibility'] = visibility[criterion['id']]
    path = tmp_path / 'mine.yaml'
    path.write_text(yaml.safe_dump(data))
    return rubrics.load(str(path))


def hidden_alice(tmp_path):
    """alice, whose failed avoid_stops is hidden and failed executable shown after the deadline."""
    rubric = rubric_with(tmp_path, avoid_stops='hidden', executable='after_due_date')
    result = alice()
    visibility = {c.id: c.visibility for c in rubric.criteria}
    for criterion in result['criteria']:
        criterion['visibility'] = visibility[criterion['id']]
    return result


def test_a_criterion_is_visible_unless_the_rubric_says_otherwise_and_only_gradescopes_words():
    assert {c['visibility'] for c in alice()['criteria']} == {'visible'}
    assert 'visibility' not in RUBRIC.criterion('builds').settings   # not a setting the lab's check reads


def test_an_unknown_visibility_is_refused(tmp_path):
    with pytest.raises(rubrics.RubricError, match="visibility of 'builds' must be one of visible, hidden, "
                                                 "after_due_date, after_published, not 'secret'"):
        rubric_with(tmp_path, builds='secret')


def test_the_check_prints_a_hidden_criterion_as_one_line_and_counts_only_what_it_shows(tmp_path, capsys):
    result = hidden_alice(tmp_path)
    check.print_result(result, due=DUE, now=BEFORE)
    out = capsys.readouterr().out
    hidden = [line for line in out.splitlines() if 'avoid_stops' in line]
    assert hidden == ['---- avoid_stops            %s: hidden until the teacher publishes it'
                      % RUBRIC.criterion('avoid_stops').title]
    assert '0.95 m' not in out and 'a.py is not executable' not in out and 'b.py too' not in out
    assert 'executable' in out and 'hidden until the deadline has passed' in out
    assert check.total_text(result, DUE, now=BEFORE) == '10 / 10, 2 criteria hidden (not counted)'


def test_after_the_deadline_an_after_due_date_criterion_is_shown(tmp_path, capsys):
    result = hidden_alice(tmp_path)
    check.print_result(result, due=DUE, now=AFTER)
    out = capsys.readouterr().out
    assert 'seen: a.py is not executable' in out and '    hint: b.py too' in out
    assert '0.95 m' not in out
    assert check.total_text(result, DUE, now=AFTER) == '10 / 11, 1 criterion hidden (not counted)'
    # without a deadline in the rubric, after_due_date stays hidden
    assert check.total_text(result, None) == '10 / 10, 2 criteria hidden (not counted)'


def test_a_classroom_run_hides_the_reason_but_sends_the_points(tmp_path):
    result = hidden_alice(tmp_path)
    runners = {r: classroom.decode(t) for r, t in classroom.outputs(result, DUE, now=BEFORE).items()}
    stops = runners['avoid_stops']
    assert stops['tests'][0]['message'] == 'hidden until the teacher publishes it'
    assert (stops['status'], stops['tests'][0]['score'], stops['max_score']) == ('fail', 0, 3)
    assert runners['executable']['tests'][0]['message'] == 'hidden until the deadline has passed'
    assert classroom.points(runners.values()) == (10, 14)   # Classroom's grade is the whole score
    after = classroom.decode(classroom.outputs(result, DUE, now=AFTER)['executable'])
    assert after['tests'][0]['message'] == 'a.py is not executable\nhint: b.py too'


def test_the_classroom_log_shows_what_the_student_may_see_gradescopes_log_everything(tmp_path):
    result = dict(hidden_alice(tmp_path), seconds=3)
    log = io.StringIO()
    platform_grading.report(result, log, runner_log=True, due=datetime.datetime(2999, 1, 1, tzinfo=UTC))
    text = log.getvalue()
    assert '0.95 m' not in text and 'a.py is not executable' not in text
    assert 'hidden until the teacher publishes it' in text
    assert 'total 10 / 10, 2 criteria hidden (not counted) (3 s)' in text
    teacher = io.StringIO()
    platform_grading.report(result, teacher, everything=True)
    assert 'seen: expected 0.35-0.5; seen 0.95 m' in teacher.getvalue() and 'total 10 / 14 (3 s)' in teacher.getvalue()


def test_gradescope_writes_each_tests_visibility_as_the_rubric_says(tmp_path):
    data = gradescope.from_result(hidden_alice(tmp_path))
    by_id = {t['name'].rsplit('(', 1)[1].rstrip(')'): t['visibility'] for t in data['tests']}
    assert by_id['avoid_stops'] == 'hidden' and by_id['executable'] == 'after_due_date'
    assert by_id['builds'] == 'visible' and data['visibility'] == 'visible'
    assert set(by_id.values()) <= set(rubrics.VISIBILITIES)


def test_the_teachers_report_shows_a_hidden_criterion_in_full_and_says_so(tmp_path):
    reports.write_all([hidden_alice(tmp_path)], RUBRIC, str(tmp_path))
    page = (tmp_path / 'report.html').read_text()
    assert 'expected 0.35-0.5; seen 0.95 m' in page
    assert '%s (hidden for the student)' % RUBRIC.criterion('avoid_stops').title in page


def test_a_result_read_back_takes_the_visibility_from_the_rubric_not_the_file(tmp_path):
    forged = alice()
    for criterion in forged['criteria']:
        criterion['visibility'] = 'hidden'
    results.write(forged, str(tmp_path))
    assert {c['visibility'] for c in results.read(RUBRIC, 'alice', str(tmp_path))['criteria']} == {'visible'}
