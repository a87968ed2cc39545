"""Late work: the rubric's policy, the submission's time where each platform gives it (hostile
ones too), the penalty in result.json, grades.csv and report.html, and ./grade.sh's --deadline."""
import csv
import datetime
import json
import os
import subprocess
import zipfile

import pytest
import yaml

from course_grader import grader, gradescope, reports, results, rubric as rubrics, submission
from test_reports import RUBRIC, alice

UTC = datetime.timezone.utc
DEADLINE = datetime.datetime(2026, 12, 1, 23, 59, tzinfo=datetime.timezone(datetime.timedelta(hours=1)))


def policy(**changes):
    entry = dict({'deadline': '2026-12-01T23:59+01:00', 'grace_minutes': 15, 'per_day': 10, 'cap': 50}, **changes)
    return rubrics.LatePolicy(entry, 'test.yaml')


def at(minutes_after_deadline):
    return DEADLINE + datetime.timedelta(minutes=minutes_after_deadline)


def test_a_day_late_is_each_24_hours_begun_after_deadline_and_grace():
    late = policy()
    assert late.deadline == DEADLINE
    assert [late.days_late(at(m)) for m in (-600, 0, 15)] == [0, 0, 0]     # on time, within the grace
    assert late.days_late(at(15) + datetime.timedelta(seconds=1)) == 1
    assert late.days_late(at(15 + 24 * 60)) == 1                           # exactly a day: still 1
    assert late.days_late(at(15 + 24 * 60) + datetime.timedelta(seconds=1)) == 2
    assert late.days_late(datetime.datetime(2026, 12, 1, 23, 14, 0, tzinfo=UTC)) == 0   # in another timezone
    assert late.days_late(datetime.datetime(2026, 12, 1, 23, 14, 1, tzinfo=UTC)) == 1


def test_the_penalty_is_per_day_of_the_maximum_up_to_the_cap_and_never_below_zero():
    result = alice()   # 10 / 14
    late = results.with_late(result, policy(), submission.Submitted(at(15 + 24 * 60 + 1), 'here', False))
    assert (late['raw_score'], late['late']['days_late'], late['late']['penalty_percent']) == (10, 2, 20)
    assert late['late']['penalty'] == pytest.approx(2.8) and late['score'] == pytest.approx(7.2)
    capped = results.with_late(result, policy(), submission.Submitted(at(60 * 24 * 30), 'here', False))
    assert capped['late']['penalty_percent'] == 50 and capped['score'] == pytest.approx(3)
    low = results.with_late(results.failed(RUBRIC, 'bob', 'no package'), policy(cap=100),
                            submission.Submitted(at(60 * 24 * 30), 'here', False))
    assert (low['score'], low['late']['penalty']) == (0, 0)
    on_time = results.with_late(result, policy(), submission.Submitted(at(10), 'here', False))
    assert (on_time['score'], on_time['late']['days_late']) == (10, 0)
    unknown = results.with_late(result, policy(), submission.Submitted(None, 'no time is known', False))
    assert unknown['score'] == 10 and 'no late penalty' in results.describe_late(unknown['late'])
    assert result['score'] == 10 and result['late'] is None   # the result given is not changed


@pytest.mark.parametrize('late, says', [
    ({'deadline': '2026-12-01T23:59', 'grace_minutes': 0, 'per_day': 10, 'cap': 50}, 'has no timezone'),
    ({'deadline': 'tomorrow', 'grace_minutes': 0, 'per_day': 10, 'cap': 50}, 'is not a time in ISO 8601'),
    ({'deadline': datetime.date(2026, 12, 1), 'grace_minutes': 0, 'per_day': 10, 'cap': 50}, 'with its timezone'),
    ({'deadline': None, 'grace_minutes': -1, 'per_day': 10, 'cap': 50}, 'grace_minutes must be a number of minutes'),
    ({'deadline': '9999-12-31T23:59Z', 'grace_minutes': 15, 'per_day': 10, 'cap': 50}, 'beyond the last time'),
    ({'deadline': None, 'grace_minutes': 0, 'per_day': 150, 'cap': 50}, 'late.per_day must be a number from 0 to 100'),
    ({'deadline': None, 'grace_minutes': 0, 'per_day': 10, 'cap': 'half'}, 'late.cap must be'),
    ({'deadline': None, 'grace_minutes': 0, 'per_day': 10}, 'late has no cap'),
    ({'deadline': None, 'grace_minutes': 0, 'per_day': 10, 'cap': 50, 'perday': 5}, 'gives perday'),
    ('10%', 'late must be a mapping'),
])
def test_a_broken_late_policy_is_refused_in_one_sentence(tmp_path, late, says):
    with open(RUBRIC.path) as stream:
        data = yaml.safe_load(stream)
    data['late'] = late
    path = tmp_path / 'mine.yaml'
    path.write_text(yaml.safe_dump(data, default_flow_style=False))
    with pytest.raises(rubrics.RubricError, match=says):
        rubrics.load(str(path))


def test_the_shipped_rubrics_have_a_policy_without_deadline_and_yaml_times_are_read():
    for lab in rubrics.labs():
        late = rubrics.load(lab).late
        assert late is not None and late.deadline is None and late.due() is None
        assert late.days_late(datetime.datetime(2999, 1, 1, tzinfo=UTC)) == 0   # no deadline: nothing is late
    assert policy(deadline=datetime.datetime(2026, 12, 1, 22, 59, tzinfo=UTC)).deadline == DEADLINE
    assert policy(deadline='2026-12-01T22:59Z').deadline == DEADLINE


def test_deadline_on_the_command_line(capsys):
    assert grader.parse_args(['move_turtlebot3', 'a', '--deadline', '2026-12-01T23:59+01:00']).deadline == DEADLINE
    with pytest.raises(SystemExit):
        grader.parse_args(['move_turtlebot3', 'a', '--deadline', '2026-12-01 23:59'])
    assert '--deadline 2026-12-01 23:59 has no timezone' in capsys.readouterr().err


def test_deadline_needs_a_rubric_with_a_late_policy(tmp_path, capsys):
    with open(RUBRIC.path) as stream:
        data = yaml.safe_load(stream)
    del data['late']
    path = tmp_path / 'mine.yaml'
    path.write_text(yaml.safe_dump(data))
    (tmp_path / 'alice').mkdir()
    assert grader.main(['move_turtlebot3', str(tmp_path / 'alice'), '--rubric', str(path), '--no-container',
                        '--out', str(tmp_path / 'out'), '--deadline', '2026-12-01T23:59Z']) == 2
    assert '--deadline needs the rubric\'s late policy' in capsys.readouterr().err
    assert grader.main(['move_turtlebot3', str(tmp_path / 'alice'), '--no-container', '--out', str(tmp_path / 'out'),
                        '--deadline', '9999-12-31T23:59Z']) == 2
    assert 'plus late.grace_minutes is beyond the last time a date can hold' in capsys.readouterr().err


# The submission's time, where each platform gives it.

def stamp(path, when):
    os.utime(str(path), (when.timestamp(), when.timestamp()))


def test_moodle_gives_the_time_of_its_newest_file(tmp_path):
    folder = tmp_path / 'Ann Lee_4711_assignsubmission_file_'
    folder.mkdir()
    (folder / 'first.zip').write_bytes(b'x')
    (folder / 'second.zip').write_bytes(b'x')
    stamp(folder / 'first.zip', at(-100))
    stamp(folder / 'second.zip', at(30))
    (folder / 'link.zip').symlink_to('/etc/passwd')   # a link's time is not the platform's
    found = submission.submitted(str(folder))
    assert found.time == at(30) and 'Moodle' in found.source and not found.claim
    empty = tmp_path / 'Bob_4712_assignsubmission_file_'
    empty.mkdir()
    says = ('the Moodle folder holds no file with Moodle\'s time (unpack the download with unzip, which keeps them)',)
    assert submission.submitted(str(empty))[1:2] == says


def test_a_download_unpacked_without_its_times_gives_no_time(tmp_path):
    """python3 -m zipfile -e writes each file now: its time would make every student late."""
    download = tmp_path / 'moodle.zip'
    with zipfile.ZipFile(str(download), 'w') as archive:
        archive.writestr(zipfile.ZipInfo('Ann Lee_4711_assignsubmission_file_/ros.zip', (2020, 1, 1, 0, 0, 0)), b'x')
    subprocess.run(['/usr/bin/python3', '-m', 'zipfile', '-e', str(download), str(tmp_path / 'python')], check=True)
    found = submission.submitted(str(tmp_path / 'python' / 'Ann Lee_4711_assignsubmission_file_'))
    assert found.time is None and 'unpack the download with unzip' in found.source
    kept = tmp_path / 'python' / 'Ann Lee_4711_assignsubmission_file_' / 'ros.zip'
    stamp(kept, at(-60))   # as unzip does: the time the archive gives
    assert submission.submitted(str(kept.parent)).time == at(-60)


def test_canvas_gives_its_files_time_and_names_its_late_mark(tmp_path):
    upload = tmp_path / 'leeann_late_4711_99_upload.zip'
    upload.write_bytes(b'x')
    stamp(upload, at(-5))
    found = submission.submitted(str(upload))
    assert found.time == at(-5) and found.source == 'Canvas\'s download: the time of its file (Canvas marked it late)'


def test_a_plain_folder_or_archive_has_no_time(tmp_path):
    (tmp_path / 'alice').mkdir()
    (tmp_path / 'bob.zip').write_bytes(b'x')
    assert submission.submitted(str(tmp_path / 'alice')).time is None
    assert submission.submitted(str(tmp_path / 'bob.zip')).time is None
    assert submission.submitted(str(tmp_path / 'gone')).time is None   # never raises


def git(folder, *args, date=None):
    env = {'PATH': '/usr/bin:/bin', 'HOME': str(folder), 'GIT_CONFIG_NOSYSTEM': '1',
           'GIT_AUTHOR_NAME': 's', 'GIT_AUTHOR_EMAIL': 's@x', 'GIT_COMMITTER_NAME': 's', 'GIT_COMMITTER_EMAIL': 's@x'}
    if date:
        env.update(GIT_COMMITTER_DATE=date, GIT_AUTHOR_DATE=date)
    return subprocess.run(['git', '-C', str(folder)] + list(args), env=env, check=True,
                          stdout=subprocess.PIPE).stdout.decode().strip()


def clone(tmp_path, date='2026-12-02T10:00:00+01:00'):
    folder = tmp_path / 'alice'
    folder.mkdir()
    git(folder, 'init', '-q', '-b', 'main')
    (folder / 'a.txt').write_text('a')
    git(folder, 'add', 'a.txt')
    git(folder, 'commit', '-q', '-m', 'mine', date=date)
    return folder


def test_a_clone_gives_its_last_commits_date_as_the_students_claim(tmp_path):
    folder = clone(tmp_path)
    found = submission.submitted(str(folder))
    assert found.time == datetime.datetime(2026, 12, 2, 9, 0, tzinfo=UTC)
    assert found.claim and found.source == 'the last commit of the clone'
    git(folder, 'pack-refs', '--all')   # the branch in packed-refs, the objects in a pack
    git(folder, 'gc', '-q')
    assert submission.submitted(str(folder)).time == found.time
    described = results.describe_late(results.with_late(alice(), policy(), found)['late'])
    assert '(the last commit of the clone: a claim of the student\'s own git, which the student can forge): ' \
           '1 day late, -10% of the maximum: -1.4 points' in described


def test_the_path_the_teacher_gives_may_be_a_link_to_the_clone(tmp_path):
    folder = clone(tmp_path)
    (tmp_path / 'alice-link').symlink_to(folder)
    assert submission.submitted(str(tmp_path / 'alice-link')) == submission.submitted(str(folder))


def test_a_clones_config_and_hooks_are_never_run(tmp_path):
    folder = clone(tmp_path)
    marker = tmp_path / 'ran'
    with open(str(folder / '.git' / 'config'), 'a') as config:
        config.write('[core]\n\tfsmonitor = touch %s\n\tpager = touch %s\n[alias]\n\tcat-file = !touch %s\n'
                     % (marker, marker, marker))
    for hook in ('post-checkout', 'pre-commit', 'reference-transaction'):
        (folder / '.git' / 'hooks' / hook).write_text('#!/bin/sh\ntouch %s\n' % marker)
        (folder / '.git' / 'hooks' / hook).chmod(0o755)
    assert submission.submitted(str(folder)).time is not None
    assert not marker.exists()


def test_a_hostile_git_folder_gives_a_sentence_never_an_error(tmp_path, monkeypatch):
    folder = clone(tmp_path)
    head = folder / '.git' / 'HEAD'
    head.write_text('ref: refs/../../../etc/passwd\n')
    assert submission.submitted(str(folder)) == (None, 'its .git/HEAD names no branch that can be read', True)
    head.write_text('ref: refs/heads/none\n')
    assert submission.submitted(str(folder)).source == 'its branch has no commit'
    head.unlink()
    head.symlink_to('/etc/hostname')
    assert submission.submitted(str(folder)).source == 'its .git has no readable HEAD'
    head.unlink()
    head.write_text('ref: refs/heads/main\n')
    # a commit whose date is no time (written as git would never write it)
    raw = b'tree 4b825dc642cb6eb9a060e54bf8d69288fbee4904\nauthor s <s@x> 1 +0000\n' \
          b'committer s <s@x> 99999999999999999999 +0000\n\nforged\n'
    sha = subprocess.run(['git', '-C', str(folder), 'hash-object', '--literally', '-t', 'commit', '-w', '--stdin'],
                         input=raw, stdout=subprocess.PIPE, check=True).stdout.decode().strip()
    (folder / '.git' / 'refs' / 'heads' / 'main').write_text(sha + '\n')
    found = submission.submitted(str(folder))
    assert found.time is None and 'a date that is no time (99999999999999999999 s after 1970)' in found.source
    # a loose object that is a FIFO: git waits on it, and is given up on
    fifo_sha = 'ab' * 20
    (folder / '.git' / 'objects' / 'ab').mkdir(exist_ok=True)
    os.mkfifo(str(folder / '.git' / 'objects' / 'ab' / fifo_sha[2:]))
    (folder / '.git' / 'refs' / 'heads' / 'main').write_text(fifo_sha + '\n')
    monkeypatch.setattr(submission, 'GIT_SECONDS', 1)
    assert submission.submitted(str(folder)) == (None, 'reading its last commit took more than 1 s: given up', True)


def test_a_git_that_is_a_link_or_a_file_is_not_followed(tmp_path):
    real = clone(tmp_path)
    linked = tmp_path / 'bob'
    linked.mkdir()
    (linked / '.git').symlink_to(real / '.git')
    assert submission.submitted(str(linked)) == (None, 'its .git is a link, not a folder: not read', True)
    worktree = tmp_path / 'carol'
    worktree.mkdir()
    (worktree / '.git').write_text('gitdir: %s\n' % (real / '.git'))
    assert submission.submitted(str(worktree)) == (None, 'its .git is a file, not a folder: not read', True)
    objects = tmp_path / 'dave'
    objects.mkdir()
    (objects / '.git').mkdir()
    (objects / '.git' / 'objects').symlink_to(real / '.git' / 'objects')
    assert submission.submitted(str(objects)).source == 'its .git/objects is not a folder: not read'


def test_a_commit_far_in_the_future_is_late_by_the_cap(tmp_path):
    folder = clone(tmp_path, date='@32503680000 +0000')   # the year 3000
    result = results.with_late(alice(), policy(), submission.submitted(str(folder)))
    assert result['late']['penalty_percent'] == 50 and result['score'] == pytest.approx(3)


# What the reports show.

def late_result(name, minutes, claim=False):
    result = dict(alice(), student=name, folder=name)
    return results.with_late(result, policy(), submission.Submitted(at(minutes), 'the last commit of the clone'
                                                                   if claim else 'Moodle\'s download', claim))


def test_grades_csv_keeps_its_columns_and_adds_raw_score_and_penalty_after_them(tmp_path):
    class_results = [late_result('alice', 15 + 60 * 24 + 5), late_result('bob', -3),
                     results.failed(RUBRIC, 'carol', 'no package')]
    reports.write_all(class_results, RUBRIC, str(tmp_path))
    with open(str(tmp_path / 'grades.csv')) as stream:
        rows = list(csv.DictReader(stream))
    header = list(rows[0])
    assert header == ['student', 'id', 'lab', 'score', 'max_score'] + [c.id for c in RUBRIC.criteria] + \
        ['raw_score', 'late_penalty', 'days_late', 'submitted', 'submitted_from']
    alice_row, bob_row, carol_row = rows
    assert (alice_row['score'], alice_row['raw_score'], alice_row['late_penalty'], alice_row['days_late']) == \
        ('7.2', '10', '2.8', '2')
    assert alice_row['submitted'] == at(15 + 60 * 24 + 5).isoformat()
    assert alice_row['submitted_from'] == 'Moodle\'s download'
    claimed = late_result('dave', 60, claim=True)
    reports.write_csv([claimed], RUBRIC, str(tmp_path / 'claimed.csv'))
    with open(str(tmp_path / 'claimed.csv')) as stream:
        assert next(csv.DictReader(stream))['submitted_from'] == \
            'the last commit of the clone (a claim of the student\'s own git, which the student can forge)'
    assert (bob_row['score'], bob_row['late_penalty'], bob_row['days_late']) == ('10', '0', '0')
    assert (carol_row['score'], carol_row['raw_score'], carol_row['late_penalty']) == ('0', '0', '')
    page = (tmp_path / 'report.html').read_text()
    assert '<th>before the late penalty</th><th>late</th>' in page
    assert '<td class="num">7.2 / 14</td><td class="num">10</td><td class="num">-2.8 (2 d)</td>' in page
    assert 'Late work: submitted %s (Moodle&#x27;s download): 2 days late, -20%% of the maximum: -2.8 points. ' \
           'Score 10 / 14 before the penalty, 7.2 after it.' % at(15 + 60 * 24 + 5).isoformat() in page
    assert '<h2 id="alice">alice: 7.2 / 14</h2>' in page


def test_without_a_deadline_the_reports_are_as_before(tmp_path):
    reports.write_all([alice()], RUBRIC, str(tmp_path))
    page = (tmp_path / 'report.html').read_text()
    assert 'late' not in page.lower()
    with open(str(tmp_path / 'grades.csv')) as stream:
        row = next(csv.DictReader(stream))
    assert (row['score'], row['raw_score'], row['late_penalty'], row['submitted']) == ('10', '10', '', '')


def test_gradescope_gets_the_final_score_and_the_penalty_in_its_output():
    data = gradescope.from_result(late_result('alice', 15 + 60 * 24 + 5, claim=True))
    assert data['score'] == pytest.approx(7.2)
    assert '10 / 14 before the late penalty' in data['output'] and 'which the student can forge' in data['output']
    assert sum(t['score'] for t in data['tests']) == 10   # the tests keep the criteria's points


def test_result_json_keeps_raw_score_late_and_the_final_score(tmp_path):
    result = late_result('alice', 15 + 60 * 24 + 5, claim=True)
    results.write(result, str(tmp_path))
    with open(str(tmp_path / 'result.json')) as stream:
        data = json.load(stream)
    assert (data['raw_score'], data['score']) == (10, pytest.approx(7.2))
    assert set(data['late']) == {'deadline', 'grace_minutes', 'submitted', 'source', 'claim', 'days_late',
                                 'penalty_percent', 'penalty'}
    assert data['late']['claim'] is True and data['late']['deadline'] == DEADLINE.isoformat()
    assert results.read_earlier(str(tmp_path.parent))[tmp_path.name]['score'] == pytest.approx(7.2)
