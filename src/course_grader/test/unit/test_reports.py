"""Scores, untrusted result files, and the three report formats (no ROS)."""
import csv
import json
import os
import xml.etree.ElementTree as ET

from course_grader import reports, results, rubric
from course_checks.verdict import Verdict

RUBRIC = rubric.load('move_turtlebot3')


def alice():
    return results.score(RUBRIC, {
        'builds': Verdict(True, 'built'), 'executable': Verdict(False, 'a.py is not executable', ['b.py too']),
        'trajectory_rate': Verdict(True, 'ok'), 'trajectory_circle': Verdict(True, 'ok'),
        'laser_data': Verdict(True, 'ok'), 'avoid_stops': Verdict(False, 'expected 0.35-0.5; seen 0.95 m'),
        'avoid_stays': Verdict(True, 'ok')}, 'alice', pictures=['trajectory.png'], seconds=30)


def test_score_adds_the_points_of_passed_criteria_and_unchecked_ones_get_the_error():
    assert alice()['score'] == 10 and alice()['max_score'] == 14
    failed = results.failed(RUBRIC, 'bob', 'no package named move_turtlebot3')
    assert failed['score'] == 0
    assert {c['reason'] for c in failed['criteria']} == {'no package named move_turtlebot3'}


def test_a_result_file_cannot_claim_more_than_the_rubric_gives(tmp_path):
    forged = alice()
    for criterion in forged['criteria']:
        criterion['points'] = 1000
    forged['score'] = 99999
    forged['criteria'].append({'id': 'bonus', 'points': 50, 'passed': True})
    forged['pictures'] = ['../../etc/passwd.png', 'trajectory.png']
    results.write(forged, str(tmp_path))
    read = results.read(RUBRIC, 'alice', str(tmp_path))
    assert read['score'] == 10
    assert [c['id'] for c in read['criteria']] == [c.id for c in RUBRIC.criteria]
    assert read['pictures'] == ['trajectory.png']
    (tmp_path / 'result.json').write_text('{"criteria": 3}')
    assert results.read(RUBRIC, 'alice', str(tmp_path)) is None


def test_csv_junit_and_html(tmp_path):
    class_results = [alice(), results.failed(RUBRIC, 'bob', 'the package does not build <b>')]
    (tmp_path / 'alice').mkdir()
    (tmp_path / 'alice' / 'trajectory.png').write_bytes(b'\x89PNG fake')
    (tmp_path / 'alice' / 'build.log').write_text('\n'.join('line %d' % i for i in range(100)))
    reports.write_all(class_results, RUBRIC, str(tmp_path), seconds=61)
    with open(str(tmp_path / 'grades.csv')) as stream:
        rows = list(csv.DictReader(stream))
    assert [row['student'] for row in rows] == ['alice', 'bob']
    assert list(rows[0])[:5] == ['student', 'id', 'lab', 'score', 'max_score']
    assert (rows[0]['score'], rows[0]['max_score'], rows[0]['avoid_stops'], rows[0]['laser_data']) == \
        ('10', '14', '0', '3')
    suite = ET.parse(str(tmp_path / 'junit' / 'alice.xml')).getroot()
    assert (suite.get('tests'), suite.get('failures')) == ('7', '2')
    failures = {case.get('name'): case.find('failure') for case in suite.iter('testcase')}
    assert failures['builds'] is None
    assert failures['avoid_stops'].get('message') == 'expected 0.35-0.5; seen 0.95 m'
    assert failures['executable'].text == 'a.py is not executable\nb.py too'
    page = (tmp_path / 'report.html').read_text()
    assert page.count('<h2 id=') == 2
    assert 'alice: 10 / 14' in page and 'the package does not build &lt;b&gt;' in page
    assert 'data:image/png;base64,' in page
    assert 'line 99' in page and 'line 74' not in page      # the log's tail only
    json.dumps(class_results)
    assert os.path.exists(str(tmp_path / 'junit' / 'bob.xml'))


def test_a_platforms_student_keeps_name_and_id_in_every_report(tmp_path):
    result = alice()
    result.update(student='José Núñez', student_id='4711', folder='José_Núñez_4711')
    reports.write_all([result], RUBRIC, str(tmp_path))
    with open(str(tmp_path / 'grades.csv'), encoding='utf-8') as stream:
        row = next(csv.DictReader(stream))
    assert (row['student'], row['id'], row['score']) == ('José Núñez', '4711', '10')
    assert (tmp_path / 'junit' / 'José_Núñez_4711.xml').exists()
    page = (tmp_path / 'report.html').read_text(encoding='utf-8')
    assert '<h2 id="José_Núñez_4711">José Núñez: 10 / 14</h2>' in page


def test_csv_cells_a_spreadsheet_would_run_are_text_and_numbers_stay_numbers(tmp_path):
    hyperlink = alice()
    hyperlink.update(student='=HYPERLINK("http://x","Alice")', student_id='4712', folder='HYPERLINK_x_Alice_4712')
    others = [dict(alice(), student=name, student_id=platform_id, folder='s%d' % index)
              for index, (name, platform_id) in enumerate([('+cmd', '@1'), ('-2+3', ''), ('\tTab', '\r9'),
                                                            ('Ann\nLee', '12')])]
    others[0]['criteria'][0]['points'] = -1.5   # numbers, negative ones too, are not text
    others[1]['score'] = -2
    reports.write_csv([hyperlink] + others, RUBRIC, str(tmp_path / 'grades.csv'))
    with open(str(tmp_path / 'grades.csv'), encoding='utf-8', newline='') as stream:
        rows = list(csv.reader(stream))
    assert rows[0][:5] == ['student', 'id', 'lab', 'score', 'max_score']
    assert [row[:4] for row in rows[1:]] == [
        ["'\tTab", "'\r9", 'move_turtlebot3', '10'], ["'+cmd", "'@1", 'move_turtlebot3', '10'],
        ["'-2+3", '', 'move_turtlebot3', '-2'],
        ['\'=HYPERLINK("http://x","Alice")', '4712', 'move_turtlebot3', '10'],
        ['Ann\nLee', '12', 'move_turtlebot3', '10']]
    assert rows[2][5] == '-1.5'


def test_grading_again_says_what_changed_per_student(tmp_path):
    earlier = alice()
    earlier['folder'] = 'alice'
    (tmp_path / 'alice').mkdir()
    results.write(earlier, str(tmp_path / 'alice'))
    (tmp_path / 'gone').mkdir()
    results.write(results.failed(RUBRIC, 'gone', 'no package'), str(tmp_path / 'gone'))
    (tmp_path / 'broken').mkdir()
    (tmp_path / 'broken' / 'result.json').write_text('{not json')
    previous = results.read_earlier(str(tmp_path))
    assert sorted(previous) == ['alice', 'gone']
    now = results.score(RUBRIC, {c['id']: Verdict(True, 'ok') for c in earlier['criteria']}, 'alice')
    changed = results.change(previous['alice'], now)
    assert (changed['score_before'], changed['score']) == (10, 14)
    assert changed['criteria'] == [('executable', 0, 1), ('avoid_stops', 0, 3)]
    assert results.describe_change(changed) == '; before 10 / 14: executable 0 -> 1, avoid_stops 0 -> 3'
    assert results.describe_change(results.change(previous['alice'], earlier)) == '; as before'
    assert results.describe_change(results.change(None, now)) == ''
    newcomer = results.failed(RUBRIC, 'bob', 'no package')
    page = reports.html_report([now, newcomer], RUBRIC, str(tmp_path), previous=previous)
    assert '<th>before</th>' in page
    assert 'The earlier grading into this folder gave 10 / 14; changed since: executable 0 → 1, avoid_stops 0 → 3.' \
        in page
    assert 'New: not in the earlier grading into this folder.' in page
    assert 'Graded last time into this folder, not this time: gone (0 / 14).' in page
