"""The host side of the grader that runs no student code: the output folder (grader) and what comes
back from a sandbox (sandbox)."""
import io
import os
import signal
import tarfile
import subprocess
import threading

import pytest

from course_grader import grader, results, rubric as rubrics, sandbox


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


def test_an_out_folder_that_cannot_be_written_is_refused_in_one_sentence(tmp_path):
    (tmp_path / 'a_file').write_text('x')
    with pytest.raises(grader.GraderError, match=r'^--out .*/a_file/grades cannot be written \(Not a directory\): '
                                                 r'nothing was graded$'):
        grader.prepare_out(str(tmp_path / 'a_file' / 'grades'))
    assert grader.main(['my_turtle', str(tmp_path), '--no-container', '--out', str(tmp_path / 'a_file' / 'g')]) == 2


def test_only_regular_files_come_back_from_a_sandbox_within_the_size_limit(tmp_path, monkeypatch):
    staging, folder = tmp_path / 'staging', tmp_path / 'alice'
    staging.mkdir()
    folder.mkdir()
    (staging / 'build.log').write_text('built')
    (staging / 'huge.log').write_bytes(b'x' * 2000)
    (staging / 'a_big_run.bag').write_bytes(b'x' * 700)   # before result.json by name, not by rank
    (staging / 'result.json').write_text('{}' + ' ' * 398)
    os.symlink('/etc/passwd', str(staging / 'passwd.log'))
    (staging / 'sub').mkdir()
    monkeypatch.setattr(sandbox, 'MAX_COPIED_BYTES', 1000)
    sandbox.copy_output(str(staging), str(folder))
    assert sorted(os.listdir(str(folder))) == ['build.log', 'result.json']


def test_only_regular_files_of_the_trusted_sides_tar_stream_are_unpacked(tmp_path):
    stream = io.BytesIO()
    with tarfile.open(fileobj=stream, mode='w') as archive:
        for name, kind in (('result.json', tarfile.REGTYPE), ('../escaped', tarfile.REGTYPE),
                           ('sub/inner.log', tarfile.REGTYPE), ('link.log', tarfile.SYMTYPE), ('dir', tarfile.DIRTYPE)):
            info = tarfile.TarInfo(name)
            info.type = kind
            data = b'{}' if kind == tarfile.REGTYPE else b''
            info.size = len(data)
            if kind == tarfile.SYMTYPE:
                info.linkname = '/etc/passwd'
            archive.addfile(info, io.BytesIO(data))
    staging = tmp_path / 'staging'
    staging.mkdir()
    sandbox.unpack_output(stream.getvalue(), str(staging))
    assert os.listdir(str(staging)) == ['result.json']
    sandbox.unpack_output(b'not a tar stream', str(staging))   # a session that broke down: nothing more
    assert not (tmp_path / 'escaped').exists()


def test_the_steps_a_session_reports_reach_on_step_and_the_whole_output_its_log(tmp_path):
    steps = []
    session_output = io.BytesIO(b'grade_submission: built in 4.1 s\nroscore started\n'
                                b'grade_submission: move_turtle.launch checked in 9.5 s\n')
    log = io.BytesIO()
    sandbox.copy_steps(session_output, log, steps.append)
    assert steps == ['built in 4.1 s', 'move_turtle.launch checked in 9.5 s']
    assert log.getvalue() == session_output.getvalue()


def test_a_session_sending_more_than_the_limit_is_read_to_its_end_and_cut():
    reader, writer = os.pipe()
    sender = subprocess.Popen(['head', '-c', '300000', '/dev/zero'], stdout=writer)
    os.close(writer)
    kept = bytearray()
    with os.fdopen(reader, 'rb') as pipe:
        sandbox.read_at_most(pipe, kept, 1000)
    assert sender.wait(10) == 0   # never blocked on a full pipe
    assert kept == b'\0' * 1000


def test_ctrl_c_while_grading_gives_no_grade_to_the_gradings_it_cut_short(tmp_path, monkeypatch, capsys):
    # Four students, two at a time: alice is graded, then bob and carol are under way when the
    # teacher presses Ctrl-C (their sessions got it too and end), and dave never starts.
    students = []
    for name in ('alice', 'bob', 'carol', 'dave'):
        (tmp_path / name).mkdir()
        students.append(str(tmp_path / name))
    out = tmp_path / 'grades'
    grader.prepare_out(str(out))
    rubric = rubrics.load('my_turtle')
    class_grader = grader.Grader(rubric, str(out), sandbox.Options(image=None), jobs=2)
    under_way = []
    both_under_way = threading.Event()

    def fake_grade(path, student, folder, scratch):
        if student != 'alice':
            under_way.append(student)
            if len(under_way) == 2:
                both_under_way.set()
            assert class_grader.interrupted.wait(30), 'no Ctrl-C came'
            return results.failed(rubric, student, 'the grading stopped with exit status 130')
        return results.failed(rubric, student, 'graded')

    monkeypatch.setattr(class_grader, '_grade', fake_grade)
    main_thread = threading.get_ident()

    def press_ctrl_c():
        assert both_under_way.wait(30)
        signal.pthread_kill(main_thread, signal.SIGINT)

    previous_handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        teacher = threading.Thread(target=press_ctrl_c)
        teacher.start()
        with pytest.raises(KeyboardInterrupt):
            class_grader.grade_all(students)
        teacher.join()
    finally:
        signal.signal(signal.SIGINT, previous_handler)
    assert sorted(under_way) == ['bob', 'carol']
    assert sorted(os.listdir(str(out))) == sorted([grader.MARKER, 'alice'])
    assert class_grader.done == 1
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 1 and lines[0].startswith('grade: [1/4] alice: 0 / '), lines


def test_ctrl_c_ends_the_grading_in_one_sentence_and_exit_130(tmp_path, monkeypatch, capsys):
    (tmp_path / 'alice').mkdir()

    def interrupted(self, submissions):
        raise KeyboardInterrupt
    monkeypatch.setattr(grader.Grader, 'grade_all', interrupted)
    out = tmp_path / 'grades'
    assert grader.main(['my_turtle', str(tmp_path / 'alice'), '--no-container', '--out', str(out)]) == 130
    assert capsys.readouterr().err == ('grade: interrupted (Ctrl-C) after 0 of 1 students: %s holds their results, '
                                       'but no grades.csv nor report; grade again to grade the class\n' % out)
    assert not (out / 'grades.csv').exists()
