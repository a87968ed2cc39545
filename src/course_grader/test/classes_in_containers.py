"""The example classes graded by ./grade.sh in containers, as a teacher runs it: every example's score
and sentence (examples/grading/<lab>/expected.yaml), the hostile one included, the model's same grade
when graded again, archives, and a second grading into the same folder. Run by
tools/grade-test.sh (CI, after the Docker test): not part of ./test.sh, which never runs the hostile
examples."""
import csv
import io
import itertools
import json
import os
import shutil
import subprocess
import tarfile
import zipfile

import pytest

from course_common.process_table import command_line, marked_processes, new_mark, stop_marked, with_mark
from course_testing.verdicts import masked_figures
from example_class import EXAMPLES, ROOT, expected, labs, make_class, mismatches, outscored_twins, read_results
from hostile_archive import link_chain_archive, markers_under


def grade(lab, submissions, out, *options, temporary=None):
    """./grade.sh's result; once it has ended, nothing it started runs (its `docker run` clients
    included: they carry the mark of its environment). temporary: its TMPDIR, when given."""
    mark = new_mark('COURSE_GRADER_TEST')
    env = dict(os.environ, TMPDIR=temporary) if temporary else None
    try:
        result = subprocess.run([os.path.join(ROOT, 'grade.sh'), lab] + submissions + ['--out', out] + list(options),
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                stdin=subprocess.DEVNULL, env=with_mark(mark, env))
    finally:
        left = [command_line(pid) for pid in marked_processes(mark)]
        stop_marked(mark)
    print(result.stdout)
    assert left == []
    return result


@pytest.fixture(scope='module')
def archives(tmp_path_factory):
    """The model answer of move_turtlebot3 as a student's .zip, and a .tar.gz that reaches out."""
    folder = tmp_path_factory.mktemp('archives')
    model = os.path.join(ROOT, 'src', 'move_turtlebot3')
    zipped = str(folder / 'zipped_model.zip')
    with zipfile.ZipFile(zipped, 'w') as archive:
        for parent, _, names in os.walk(model):
            for name in names:
                path = os.path.join(parent, name)
                info = zipfile.ZipInfo(os.path.join('catkin_ws', 'src', 'move_turtlebot3',
                                                    os.path.relpath(path, model)))
                info.external_attr = (os.stat(path).st_mode & 0o777) << 16
                with open(path, 'rb') as stream:
                    archive.writestr(info, stream.read())
    traversal = str(folder / 'traversal.tar.gz')
    with tarfile.open(traversal, 'w:gz') as archive:
        info = tarfile.TarInfo('../../grader_was_here')
        info.size = 3
        archive.addfile(info, io.BytesIO(b'bad'))
    return zipped, traversal, str(folder)


def grader_containers():
    """The names of the grader's containers on the engine, running or not."""
    return set(subprocess.run(['docker', 'ps', '-a', '--format', '{{.Names}}', '--filter', 'name=course-grader-'],
                              stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout.split())


# Each lab's first grading (test_example_class_in_containers), which the gradings again compare with.
FIRST_GRADINGS = {}


def verdicts(details):
    """{student: (score, [(criterion, points, reason, hints)])}, every measured figure in the sentences
    as '#' (course_testing.verdicts)."""
    return {student: (result['score'], [(c['id'], c['points'], masked_figures(c['reason']),
                                         [masked_figures(h) for h in c['hints']])
                                        for c in result['criteria']])
            for student, result in details.items()}


@pytest.mark.parametrize('lab', labs())
def test_example_class_in_containers(lab, tmp_path):
    students = sorted(expected(lab))
    # The engine may be shared (another checkout, an earlier run stopped by force): only what this
    # grading leaves counts.
    before = grader_containers()
    out = str(tmp_path / 'grades')
    folders = make_class(lab, str(tmp_path / 'class'))
    result = grade(lab, [folders[s] for s in students], out, '--jobs', '2')
    assert result.returncode == 0, result.stdout
    for student in students:
        assert ('] %s: %g / ' % (student, expected(lab)[student]['score'])) in result.stdout
    rows, details = read_results(out)
    assert sorted(rows) == students
    assert mismatches(lab, rows, details, students) == []
    FIRST_GRADINGS[lab] = verdicts(details)
    assert outscored_twins(lab, rows) == []   # every attempt costs only the attempt
    # The model's nodes print what they print, and nothing of the sandbox (a ROS_HOME they cannot write).
    model_logs = [name for name in os.listdir(os.path.join(out, 'model')) if name.endswith('.log')]
    assert model_logs
    for name in model_logs:
        with open(os.path.join(out, 'model', name), errors='replace') as stream:
            assert 'cannot create log directory' not in stream.read(), name
    assert os.path.isfile(os.path.join(out, 'report.html'))
    assert sorted(os.listdir(os.path.join(out, 'junit'))) == sorted(s + '.xml' for s in students)
    # sim compared the class in containers of the image (the host may have no sim: Debian 13).
    with open(os.path.join(out, 'similarity.json'), encoding='utf-8') as stream:
        similar = json.load(stream)
    assert (similar['error'], similar['image']) == (None, os.environ['COURSE_GRADER_IMAGE'])
    assert 'not isolated' not in result.stdout
    if lab == 'move_turtlebot3':
        # into_the_wall and each student made of it with one attack more (its twin) share its changed
        # line (each patch repeats it); no one else shares anything beyond the given material (the
        # other patches of the model change other lines: timed_drive's avoid_obstacle.py, say).
        sharing = sorted(s for s in students if s == 'into_the_wall' or expected(lab)[s].get('twin') == 'into_the_wall')
        with open(os.path.join(out, 'similarity.csv'), encoding='utf-8') as stream:
            pairs = sorted((row['student_a'], row['student_b']) for row in csv.DictReader(stream))
        assert len(sharing) >= 3 and pairs == list(itertools.combinations(sharing, 2))
    # Nothing left running, nothing written where the hostile one tried to write.
    assert grader_containers() - before == set()
    for parent, _, names in os.walk(ROOT):
        assert 'hostile_was_here' not in names, parent


@pytest.mark.parametrize('lab', labs())
def test_the_same_grade_every_time(lab, tmp_path):
    """The model graded twice more, side by side (two submissions at a time, as the first grading:
    the load a teacher's grading has): both times it gets the same points for every criterion, for
    the same reasons, as in the class's first grading. Every other student's score and sentences
    are pinned at each grading of the class (expected.yaml), so that each CI run grades them again
    against the same figures. Graded a second time in the same run, the honest students took 222 s
    of CI's grader step (136, 53 and 33 s on 2026-12-03), the hostile ones (`hostile`'s fork bombs
    and floods run into the sandbox's limits) about as long again."""
    folders = make_class(lab, str(tmp_path / 'class'))
    twice = [folders['model'], str(tmp_path / 'again' / 'model_again')]
    shutil.copytree(folders['model'], twice[1], symlinks=True)
    if lab not in FIRST_GRADINGS:   # run alone (-k): the first grading here
        out = str(tmp_path / 'first')
        assert grade(lab, [folders['model']], out).returncode == 0
        FIRST_GRADINGS[lab] = verdicts(read_results(out)[1])
    out = str(tmp_path / 'twice')
    assert grade(lab, twice, out, '--jobs', '2').returncode == 0
    first = FIRST_GRADINGS[lab]['model']
    again = verdicts(read_results(out)[1])
    assert sorted(again) == ['model', 'model_again']
    differences = ['%s: %r the first time, %r now' % (name, first, again[name]) for name in sorted(again)
                   if again[name] != first]
    assert differences == []


def test_archives_and_grading_again_into_the_same_folder(archives, tmp_path):
    zipped, traversal, folder = archives
    out = str(tmp_path / 'grades')
    # Issue 31's link chain around into_the_wall: an unpacker writing through the links would leave
    # the marker in the grader's temporary folder, beside the scratch folder it unpacks in.
    into_the_wall = make_class('move_turtlebot3', str(tmp_path / 'class'))['into_the_wall']
    link_chain = link_chain_archive(str(tmp_path / 'link_chain.tar.gz'), os.path.join(into_the_wall, 'move_turtlebot3'))
    temporary = tmp_path / 'tmp'
    temporary.mkdir()
    model = os.path.join(EXAMPLES, 'move_turtlebot3', 'model')
    result = grade('move_turtlebot3', [zipped, traversal, link_chain, model], out, temporary=str(temporary))
    assert result.returncode == 0, result.stdout
    rows, details = read_results(out)
    assert rows['zipped_model']['score'] == rows['model']['score'] == '14'   # the same code, the same score
    assert markers_under(str(tmp_path), folder) == []
    assert float(rows['link_chain']['score']) <= expected('move_turtlebot3')['into_the_wall']['score']
    assert rows['traversal']['score'] == '0'
    assert "the archive holds '../../grader_was_here', which points outside its folder: refused" == \
        details['traversal']['error']
    assert not os.path.exists(os.path.join(os.path.dirname(folder), 'grader_was_here'))
    # Again into the same folder, one student only: the old results are gone, not mixed in.
    result = grade('move_turtlebot3', [traversal], out)
    assert result.returncode == 0, result.stdout
    rows, _ = read_results(out)
    assert sorted(rows) == ['traversal']
    assert sorted(os.listdir(out)) == ['.course_grader', 'grades.csv', 'junit', 'report.html', 'similarity.csv',
                                       'similarity.json', 'traversal']
    assert os.listdir(os.path.join(out, 'junit')) == ['traversal.xml']


def test_the_grader_itself_failing_says_why_with_status_2(tmp_path):
    result = grade('no_such_lab', [str(tmp_path)], str(tmp_path / 'out'), '--no-container')
    assert result.returncode == 2
    assert "grade: no rubric for lab 'no_such_lab' (the labs are: " in result.stdout
    result = grade('move_turtlebot3', [str(tmp_path / 'nobody')], str(tmp_path / 'out'), '--no-container')
    assert (result.returncode, result.stdout.splitlines()[-1]) == (2, 'grade: no such submission: %s' % (tmp_path / 'nobody'))
    (tmp_path / 'mine').mkdir()
    (tmp_path / 'mine' / 'thesis.tex').write_text('precious')
    result = grade('move_turtlebot3', [os.path.join(EXAMPLES, 'move_turtlebot3', 'model')], str(tmp_path / 'mine'))
    assert result.returncode == 2
    assert 'holds files the grader did not write: give an empty or new folder' in result.stdout
    assert (tmp_path / 'mine' / 'thesis.tex').read_text() == 'precious'
