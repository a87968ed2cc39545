"""The student's check keeps the last build of a lab (grading_session.BuildCache): kept only while
the package's files are the same by name and its build description the same to the byte; a file
whose contents changed is copied (dated now, so that make rebuilds it), the others left as they were."""
import os
import types

import pytest

from course_grader import grading_session
from course_grader.grading_session import BuildCache


def package(folder, files):
    for name, text in files.items():
        path = os.path.join(folder, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w') as stream:
            stream.write(text)
    return folder


FILES = {'CMakeLists.txt': 'project(p)\n', 'package.xml': '<package/>\n', 'src/a.cpp': 'int a;\n',
         'msg/M.msg': 'int32 x\n', 'scripts/s.py': 'print(1)\n'}


def test_the_key_follows_the_build_description_and_the_names_not_the_sources(tmp_path):
    folder = package(str(tmp_path / 'p'), FILES)
    key = BuildCache.key(folder)
    package(folder, {'src/a.cpp': 'int b;\n', 'scripts/s.py': 'print(2)\n'})
    assert BuildCache.key(folder) == key
    for changed in ({'CMakeLists.txt': 'project(q)\n'}, {'msg/M.msg': 'int64 x\n'}, {'src/new.cpp': ''}):
        other = package(str(tmp_path / ('o%d' % len(os.listdir(str(tmp_path))))), dict(FILES, **changed))
        assert BuildCache.key(other) != key, changed


def test_a_package_with_a_link_is_built_afresh(tmp_path):
    folder = package(str(tmp_path / 'p'), FILES)
    os.symlink('a.cpp', os.path.join(folder, 'src', 'b.cpp'))
    assert BuildCache.key(folder) is None
    assert BuildCache(str(tmp_path / 'cache')).prepare(folder, 'p') is None


def test_only_changed_files_are_copied_and_a_new_description_empties_the_workspace(tmp_path):
    folder = package(str(tmp_path / 'p'), FILES)
    cache = BuildCache(str(tmp_path / 'cache'))
    assert cache.acquire()
    workspace = cache.prepare(folder, 'p')
    copy = os.path.join(workspace, 'src', 'p')
    built = os.path.join(workspace, 'build', 'made')
    package(os.path.join(workspace, 'build'), {'made': ''})
    for name in FILES:
        os.utime(os.path.join(copy, name), (1, 1))
    package(folder, {'src/a.cpp': 'int b;\n'})
    assert cache.prepare(folder, 'p') == workspace
    assert os.path.getmtime(os.path.join(copy, 'src/a.cpp')) > 1
    assert open(os.path.join(copy, 'src/a.cpp')).read() == 'int b;\n'
    assert os.path.getmtime(os.path.join(copy, 'CMakeLists.txt')) == 1
    assert os.path.exists(built)
    package(folder, {'CMakeLists.txt': 'project(q)\n'})
    cache.prepare(folder, 'p')
    assert not os.path.exists(built)


def test_one_session_at_a_time_holds_it(tmp_path):
    first, second = BuildCache(str(tmp_path / 'cache')), BuildCache(str(tmp_path / 'cache'))
    assert first.acquire()
    assert not second.acquire()


def failing_builds(monkeypatch, timed_out=False):
    """_build replaced by one that compiles an object into its workspace and fails; the list of its
    builds: (in the cache's workspace, whether it began with an object there)."""
    builds = []

    def failing_build(session, workspace, copy_from, jobs):
        made = os.path.join(workspace, 'build', 'a.o')
        builds.append((copy_from is None, os.path.exists(made)))
        package(os.path.join(workspace, 'build'), {'a.o': ''})
        raise grading_session.BuildFailed('first compiler error: a.cpp line 1: expected', timed_out=timed_out)

    monkeypatch.setattr(grading_session, '_build', failing_build)
    return builds


def check_build(tmp_path, folder):
    session = types.SimpleNamespace(package_dir=folder, rubric=types.SimpleNamespace(package='p'))
    with pytest.raises(grading_session.BuildFailed, match='a.cpp line 1'):
        grading_session.build(session, str(tmp_path / 'scratch'), BuildCache(str(tmp_path / 'cache')))


def test_a_failed_build_is_done_again_afresh_only_when_it_began_from_a_kept_one(tmp_path, monkeypatch):
    folder = package(str(tmp_path / 'p'), FILES)
    builds = failing_builds(monkeypatch)
    # The first check: the cache's workspace begins empty, so its failure is a fresh build's.
    check_build(tmp_path, folder)
    assert builds == [(True, False)]
    # The next check: the kept build, with what the failed one compiled; it fails too, so a fresh
    # build follows, in the emptied cache.
    builds.clear()
    check_build(tmp_path, folder)
    assert builds == [(True, True), (True, False)]
    # What that fresh build compiled is kept for the check after.
    assert os.path.exists(str(tmp_path / 'cache' / 'ws' / 'build' / 'a.o'))


def test_a_build_stopped_at_its_time_limit_is_neither_kept_nor_done_again(tmp_path, monkeypatch):
    folder = package(str(tmp_path / 'p'), FILES)
    builds = failing_builds(monkeypatch)
    check_build(tmp_path, folder)
    builds = failing_builds(monkeypatch, timed_out=True)
    check_build(tmp_path, folder)
    assert builds == [(True, True)]
    assert not os.path.exists(str(tmp_path / 'cache' / 'ws'))
