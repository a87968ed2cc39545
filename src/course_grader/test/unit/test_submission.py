"""Unpacking submissions safely and finding the lab's package in them (no ROS)."""
import io
import os
import tarfile
import zipfile

import pytest

from course_grader import submission
from course_grader.submission import SubmissionError

PACKAGE_XML = '<package format="2"><name>move_turtlebot3</name></package>'


def tar_with(path, members):
    """members: (name, bytes or None for a folder, or ('link', target) / ('hard', target))."""
    with tarfile.open(path, 'w:gz') as tar:
        for name, content in members:
            info = tarfile.TarInfo(name)
            if isinstance(content, tuple):
                info.type = tarfile.SYMTYPE if content[0] == 'link' else tarfile.LNKTYPE
                info.linkname = content[1]
                tar.addfile(info)
            elif content is None:
                info.type = tarfile.DIRTYPE
                tar.addfile(info)
            else:
                info.size = len(content)
                info.mode = 0o755
                tar.addfile(info, io.BytesIO(content))
    return str(path)


def test_student_names_from_folders_and_archives(tmp_path):
    assert submission.student_of('/x/alice.tar.gz') == ('alice', '', 'alice')
    assert submission.student_of('/x/bob.zip') == ('bob', '', 'bob')
    assert submission.student_of('/x/carol/') == ('carol', '', 'carol')
    assert submission.student_of('/x/d a$n.zip') == ('d a$n', '', 'd_a_n')


def test_a_moodle_folder_keeps_the_name_as_moodle_wrote_it_and_its_id(tmp_path):
    folder = tmp_path / 'José Núñez_4711_assignsubmission_file_'
    folder.mkdir()
    assert submission.student_of(str(folder)) == ('José Núñez', '4711', 'José_Núñez_4711')
    # Unzipped on a Mac, the accents come decomposed: the same student, the same folder.
    decomposed = tmp_path / 'Jose\u0301 Nu\u0301n\u0303ez_4711_assignsubmission_file_'
    decomposed.mkdir()
    assert submission.student_of(str(decomposed)) == ('José Núñez', '4711', 'José_Núñez_4711')
    assert submission.ascii_name('José_Núñez_4711') == 'Jose_Nunez_4711'


def test_a_platforms_name_may_hold_a_line_break():
    assert submission.student_of('/d/Ann\nLee_12_assignsubmission_file_') == ('Ann\nLee', '12', 'Ann_Lee_12')


def test_a_canvas_file_gives_the_name_and_the_user_id():
    assert submission.student_of('/d/nunezjose_4711_998877_catkin_ws.zip') == ('nunezjose', '4711', 'nunezjose_4711')
    assert submission.student_of('/d/smithanna_late_4712_998878_upload.tar.gz') == ('smithanna', '4712', 'smithanna_4712')


def zip_with(path, members):
    with zipfile.ZipFile(str(path), 'w') as archive:
        for name, content in members:
            archive.writestr(name, content)
    return str(path)


def test_the_one_archive_in_a_platforms_folder_is_what_is_graded(tmp_path):
    folder = tmp_path / 'José Núñez_4711_assignsubmission_file_'
    folder.mkdir()
    zip_with(folder / 'catkin_ws.zip', [('catkin_ws/src/move_turtlebot3/package.xml', PACKAGE_XML)])
    (folder / 'notes.txt').write_text('my report')
    out = tmp_path / 'out'
    out.mkdir()
    unpacked = submission.unpack(str(folder), str(out))
    assert unpacked == str(out.resolve())
    assert submission.find_package(unpacked, 'move_turtlebot3') == 'catkin_ws/src/move_turtlebot3'


def test_loose_files_in_a_platforms_folder_are_graded_as_they_are(tmp_path):
    package = tmp_path / 'Ann Lee_12_assignsubmission_file_' / 'move_turtlebot3'
    package.mkdir(parents=True)
    (package / 'package.xml').write_text(PACKAGE_XML)
    zip_with(package / 'old.zip', [('x.txt', 'an old copy')])   # beside a package: not the upload
    assert submission.unpack(str(package.parent), str(tmp_path)) == str(package.parent)


def test_two_archives_and_no_package_are_named(tmp_path):
    folder = tmp_path / 'Ann Lee_12_assignsubmission_file_'
    folder.mkdir()
    zip_with(folder / 'a.zip', [('x.txt', 'x')])
    tar_with(folder / 'b.tar.gz', [('y.txt', b'y')])
    with pytest.raises(SubmissionError, match=r'^the folder holds 2 archives and no package.xml '
                                              r'\(a.zip, b.tar.gz\): hand in one$'):
        submission.unpack(str(folder), str(tmp_path))


def test_tar_unpacks_with_execute_bits_and_the_package_is_found(tmp_path):
    archive = tar_with(tmp_path / 'alice.tar.gz', [
        ('ws/src/move_turtlebot3/package.xml', PACKAGE_XML.encode()),
        ('ws/src/move_turtlebot3/scripts/trajectory.py', b'#!/usr/bin/env python3\n'),
        ('ws/src/move_turtlebot3/scripts/link.py', ('link', 'trajectory.py'))])
    out = tmp_path / 'out'
    out.mkdir()
    folder = submission.unpack(archive, str(out))
    assert submission.find_package(folder, 'move_turtlebot3') == 'ws/src/move_turtlebot3'
    script = os.path.join(folder, 'ws/src/move_turtlebot3/scripts/trajectory.py')
    assert os.access(script, os.X_OK)
    assert submission.find_file(os.path.join(folder, 'ws/src/move_turtlebot3'), 'trajectory.py') == \
        ['scripts/trajectory.py']


@pytest.mark.parametrize('members, message', [
    ([('../evil.py', b'x')], r"^the archive holds '../evil.py', which points outside its folder: refused$"),
    ([('ok/../../evil.py', b'x')], 'points outside its folder'),
    ([('/etc/evil', b'x')], r"^the archive holds '/etc/evil', an absolute path: refused$"),
    ([('a', b'x'), ('a/b', b'y')], r"^the archive holds 'a' both as a file and as a folder: refused$"),
    ([('a/b', b'x'), ('a', b'y')], "holds 'a' both as a file and as a folder"),
    ([('a/b', b'x'), ('a/b', b'y')], r"^the archive holds 'a/b' twice: refused$"),
    ([('caf\u00e9', b'x'), ('cafe\u0301', b'y')], "holds 'caf\u00e9' twice"),   # NFC and NFD: one name
])
def test_tar_path_traversal_and_clashing_names_are_refused_before_anything_is_written(tmp_path, members, message):
    archive = tar_with(tmp_path / 'mallory.tar.gz', [('first.txt', b'x')] + members)
    out = tmp_path / 'out'
    out.mkdir()
    with pytest.raises(SubmissionError, match=message):
        submission.unpack(archive, str(out))
    assert os.listdir(str(out)) == []
    assert not (tmp_path / 'evil.py').exists()


def test_links_are_skipped_not_made_and_named(tmp_path):
    # A catkin workspace's src/CMakeLists.txt is an absolute link: the rest of it is graded.
    archive = tar_with(tmp_path / 'ws.tar.gz', [
        ('ws/src/CMakeLists.txt', ('link', '/usr/share/catkin/cmake/toplevel.cmake')),
        ('ws/src/out', ('link', '../../..')),
        ('ws/src/hard', ('hard', '../../etc/passwd')),
        ('ws/src/move_turtlebot3/package.xml', PACKAGE_XML.encode())])
    out = tmp_path / 'out'
    out.mkdir()
    skipped = []
    folder = submission.unpack(archive, str(out), skipped)
    assert submission.find_package(folder, 'move_turtlebot3') == 'ws/src/move_turtlebot3'
    assert sorted(os.listdir(os.path.join(folder, 'ws', 'src'))) == ['move_turtlebot3']
    assert skipped == ["ws/src/CMakeLists.txt (a link to '/usr/share/catkin/cmake/toplevel.cmake')",
                       "ws/src/out (a link to '../../..')", "ws/src/hard (a hard link to '../../etc/passwd')"]


def test_nothing_is_written_through_a_chain_of_links(tmp_path):
    # l1 -> ., l1/l2 -> .., l2/l3 -> .. once wrote l2/l3/marker.txt beside the unpacking folder.
    archive = tar_with(tmp_path / 'chain.tar.gz', [
        ('l1', ('link', '.')), ('l1/l2', ('link', '..')), ('l2/l3', ('link', '..')), ('l2/l3/marker.txt', b'x')])
    out = tmp_path / 'out'
    out.mkdir()
    submission.unpack(archive, str(out))
    assert sorted(str(path.relative_to(tmp_path)) for path in tmp_path.rglob('marker.txt')) == \
        ['out/l2/l3/marker.txt']
    assert not any(path.is_symlink() for path in out.rglob('*'))


def test_a_zip_entry_marked_as_a_link_is_skipped(tmp_path):
    archive = str(tmp_path / 'links.zip')
    with zipfile.ZipFile(archive, 'w') as zipped:
        link = zipfile.ZipInfo('passwd')
        link.external_attr = (0o120777) << 16
        zipped.writestr(link, '/etc/passwd')
        zipped.writestr('notes.txt', 'mine')
    out = tmp_path / 'out'
    out.mkdir()
    skipped = []
    submission.unpack(archive, str(out), skipped)
    assert os.listdir(str(out)) == ['notes.txt']
    assert skipped == ['passwd (a link)']


def test_a_fifo_or_a_link_to_one_in_a_folder_is_refused_and_never_opened(tmp_path):
    folder = tmp_path / 'Ann Lee_12_assignsubmission_file_'
    folder.mkdir()
    os.mkfifo(str(folder / 'package.xml'))
    assert submission.package_name(str(folder / 'package.xml')) is None   # answers at once
    with pytest.raises(SubmissionError, match=r'^package.xml is a FIFO \(named pipe\), not a file: refused$'):
        submission.unpack(str(folder), str(tmp_path))
    os.remove(str(folder / 'package.xml'))
    os.mkfifo(str(tmp_path / 'alice.zip'))
    os.symlink(str(tmp_path / 'alice.zip'), str(folder / 'alice.zip'))   # a link is never the upload
    assert submission.upload_inside(str(folder)) is None
    with pytest.raises(SubmissionError, match=r'^alice.zip is a FIFO \(named pipe\), not an archive: refused$'):
        submission.unpack(str(tmp_path / 'alice.zip'), str(tmp_path))


def test_names_for_the_terminal_are_one_line_with_escapes_shown():
    assert submission.terminal_text('José Núñez') == 'José Núñez'
    assert submission.terminal_text('Ann\nLee\x1b[2J\u202etxt.exe\r') == 'Ann\\nLee\\x1b[2J\\u202etxt.exe\\r'
    assert submission.terminal_text('Traceback:\n  \x1b]0;title\x07', keep_lines=True) == \
        'Traceback:\n  \\x1b]0;title\\x07'


def test_zip_traversal_bomb_and_garbage_are_refused(tmp_path, monkeypatch):
    out = tmp_path / 'out'
    out.mkdir()
    evil = tmp_path / 'evil.zip'
    with zipfile.ZipFile(str(evil), 'w') as zipped:
        zipped.writestr('../../outside.txt', 'x')
    with pytest.raises(SubmissionError, match='outside its folder'):
        submission.unpack(str(evil), str(out))
    bomb = tmp_path / 'bomb.zip'
    with zipfile.ZipFile(str(bomb), 'w', zipfile.ZIP_DEFLATED) as zipped:
        zipped.writestr('zeros', b'\0' * (3 * 2 ** 20))
    monkeypatch.setattr(submission, 'MAX_UNPACKED_BYTES', 2 ** 20)
    with pytest.raises(SubmissionError, match='more than 1 MB'):
        submission.unpack(str(bomb), str(out))
    garbage = tmp_path / 'garbage.zip'
    garbage.write_bytes(b'not a zip')
    with pytest.raises(SubmissionError, match='not a readable .zip'):
        submission.unpack(str(garbage), str(out))
    (tmp_path / 'x.rar').write_text('')
    with pytest.raises(SubmissionError, match='neither a folder nor'):
        submission.unpack(str(tmp_path / 'x.rar'), str(out))


def test_tar_bomb_is_refused_before_anything_is_written(tmp_path, monkeypatch):
    monkeypatch.setattr(submission, 'MAX_UNPACKED_BYTES', 1000)
    archive = tar_with(tmp_path / 'bomb.tar.gz', [('a', b'x' * 600), ('b', b'x' * 600)])
    out = tmp_path / 'out'
    out.mkdir()
    with pytest.raises(SubmissionError, match='unpacks to more than'):
        submission.unpack(archive, str(out))
    assert os.listdir(str(out)) == []


def test_folder_with_a_link_out_is_refused(tmp_path):
    folder = tmp_path / 'eve'
    folder.mkdir()
    os.symlink('/etc/passwd', str(folder / 'passwd'))
    with pytest.raises(SubmissionError, match='passwd is a link to /etc/passwd, outside the submission'):
        submission.unpack(str(folder), str(tmp_path))


def test_missing_or_twice_present_package_is_named(tmp_path):
    (tmp_path / 'other').mkdir()
    (tmp_path / 'other' / 'package.xml').write_text('<package><name>my_turtle</name></package>')
    with pytest.raises(SubmissionError, match=r'no package named move_turtlebot3 .* found: my_turtle \(other\)'):
        submission.find_package(str(tmp_path), 'move_turtlebot3')
    for copy in ('a', 'b'):
        (tmp_path / copy).mkdir()
        (tmp_path / copy / 'package.xml').write_text(PACKAGE_XML)
    with pytest.raises(SubmissionError, match='there 2 times'):
        submission.find_package(str(tmp_path), 'move_turtlebot3')
