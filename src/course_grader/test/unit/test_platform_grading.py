"""What the platforms hand in, before anything runs: each bad input one sentence (no ROS run)."""
import io
import json
import os
import shutil
import zipfile

import pytest

from course_grader import platform_grading, results, rubric as rubrics
from course_grader.submission import SubmissionError

RUBRIC = rubrics.load('my_turtle')
MODEL = os.path.join(os.path.dirname(__file__), '..', '..', '..', '..', 'examples', 'grading', 'my_turtle', 'model')


def staged(folder, tmp_path):
    staging = tmp_path / 'staging'
    staging.mkdir()
    return platform_grading.stage(str(folder), RUBRIC, str(staging)), staging


def test_an_empty_repository_says_so(tmp_path):
    (tmp_path / 'repo' / '.git').mkdir(parents=True)
    (tmp_path / 'repo' / '.github').mkdir()
    with pytest.raises(SubmissionError) as error:
        staged(tmp_path / 'repo', tmp_path)
    assert str(error.value) == ('the submission is empty: hand in the package my_turtle (the folder made by '
                                'catkin_create_pkg my_turtle), at the top or in src/')


@pytest.mark.parametrize('layout, sentence', [
    ({'README.md': 'my notes'}, 'no package named my_turtle in the submission (a folder with a package.xml saying '
                                '<name>my_turtle</name>); packages found: none'),
    ({'my_turtle/package.xml': '<package><name>turtle_mine</name></package>'},
     'packages found: turtle_mine (my_turtle)'),
    ({'a/my_turtle/package.xml': '<package><name>my_turtle</name></package>',
      'b/my_turtle/package.xml': '<package><name>my_turtle</name></package>'},
     'the package my_turtle is there 2 times (a/my_turtle, b/my_turtle): hand in one'),
])
def test_no_package_another_name_and_two_copies_are_one_sentence(tmp_path, layout, sentence):
    for name, text in layout.items():
        path = tmp_path / 'repo' / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    with pytest.raises(SubmissionError, match='^[^\n]*$') as error:
        staged(tmp_path / 'repo', tmp_path)
    assert sentence in str(error.value)


def test_the_package_at_the_top_or_in_src_is_copied_readable_by_everyone_without_git_history(tmp_path):
    repo = tmp_path / 'repo'
    shutil.copytree(MODEL, str(repo / 'src' / 'my_turtle'))
    (repo / '.git').mkdir()
    (repo / '.git' / 'packed').write_bytes(b'x' * 1000)
    os.chmod(str(repo / 'src' / 'my_turtle' / 'package.xml'), 0o600)
    package, staging = staged(repo, tmp_path)
    assert package == 'src/my_turtle'
    assert os.stat(str(staging / package / 'package.xml')).st_mode & 0o777 == 0o644
    assert os.stat(str(staging)).st_mode & 0o777 == 0o755
    assert not (staging / '.git').exists()
    (tmp_path / 'again').mkdir()
    assert staged(repo / 'src' / 'my_turtle', tmp_path / 'again')[0] == '.'


def test_one_uploaded_zip_is_unpacked(tmp_path):
    upload = tmp_path / 'upload'
    upload.mkdir()
    with zipfile.ZipFile(str(upload / 'catkin_ws.zip'), 'w') as archive:
        archive.writestr('catkin_ws/src/my_turtle/package.xml', '<package><name>my_turtle</name></package>')
    package, _ = staged(upload, tmp_path)
    assert package == 'catkin_ws/src/my_turtle'


def test_a_link_out_of_the_submission_is_refused(tmp_path):
    (tmp_path / 'repo').mkdir()
    os.symlink('/etc', str(tmp_path / 'repo' / 'etc'))
    with pytest.raises(SubmissionError, match='is a link to /etc, outside the submission: refused'):
        staged(tmp_path / 'repo', tmp_path)


def test_the_runner_log_cannot_carry_a_workflow_command():
    result = results.failed(RUBRIC, 'mallory', 'x\n::set-output name=builds::forged')
    stream = io.StringIO()
    platform_grading.report(dict(result, seconds=1), stream, runner_log=True)
    lines = stream.getvalue().splitlines()
    token = lines[0].split('::stop-commands::')[1]
    assert len(token) == 32 and lines[-1] == '::%s::' % token
    assert '::set-output name=builds::forged' in stream.getvalue()   # shown, between the two


def test_gradescopes_results_replace_a_link_planted_at_their_name_and_never_write_through_it(tmp_path):
    results_folder, elsewhere = tmp_path / 'results', tmp_path / 'forged.json'
    results_folder.mkdir()
    elsewhere.write_text('{"score": 14}')
    os.symlink('../forged.json', str(results_folder / 'results.json'))
    result = results.failed(RUBRIC, 'mallory', 'the node crashed')
    platform_grading.deliver_gradescope(result, str(results_folder), None, str(tmp_path))
    written = results_folder / 'results.json'
    assert not written.is_symlink() and json.loads(written.read_text())['score'] == 0
    assert elsewhere.read_text() == '{"score": 14}'
    assert os.listdir(str(results_folder)) == ['results.json']


def test_gradescopes_results_go_on_the_descriptor_given_and_nowhere_else(tmp_path):
    read_end, write_end = os.pipe()
    result = results.failed(RUBRIC, 'alice', 'the node crashed')
    platform_grading.deliver_gradescope(result, str(tmp_path / 'results'), write_end, str(tmp_path))
    with os.fdopen(read_end) as stream:
        assert json.load(stream)['tests'][0]['output'] == 'the node crashed'
    assert os.listdir(str(tmp_path)) == []
