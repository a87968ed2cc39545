"""The host side of the grader that runs no student code: the output folder and what comes back
from a sandbox."""
import os

import pytest

from course_grader import grader


def test_out_folder_new_then_replaced_and_a_foreign_one_refused(tmp_path):
    out = tmp_path / 'grades'
    grader.prepare_out(str(out))
    (out / 'alice').mkdir()
    (out / 'grades.csv').write_text('old')
    grader.prepare_out(str(out))
    assert sorted(os.listdir(str(out))) == [grader.MARKER]
    mine = tmp_path / 'mine'
    mine.mkdir()
    (mine / 'thesis.tex').write_text('precious')
    with pytest.raises(grader.GraderError, match='holds files the grader did not write'):
        grader.prepare_out(str(mine))
    assert (mine / 'thesis.tex').read_text() == 'precious'


def test_only_regular_files_come_back_from_a_sandbox_within_the_size_limit(tmp_path, monkeypatch):
    staging, folder = tmp_path / 'staging', tmp_path / 'alice'
    staging.mkdir()
    folder.mkdir()
    (staging / 'build.log').write_text('built')
    (staging / 'huge.log').write_bytes(b'x' * 2000)
    os.symlink('/etc/passwd', str(staging / 'passwd.log'))
    (staging / 'sub').mkdir()
    (staging / grader.PROCESS_GROUPS).write_text('1234\n')
    monkeypatch.setattr(grader, 'MAX_COPIED_BYTES', 1000)
    grader.copy_output(str(staging), str(folder))
    assert os.listdir(str(folder)) == ['build.log']


def test_process_groups_left_by_a_session_are_killed(tmp_path):
    import subprocess
    sleeper = subprocess.Popen(['sleep', '60'], start_new_session=True)
    listing = tmp_path / grader.PROCESS_GROUPS
    listing.write_text('%d\n' % sleeper.pid)
    grader.kill_process_groups(str(listing))
    assert sleeper.wait(5) == -9
    assert not listing.exists()
