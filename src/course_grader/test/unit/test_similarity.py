"""Similar submissions (course_grader.similarity): sim's output read, the given material taken out,
the files a submission offers bounded, and classes made of the example students: only the two who
share a changed node are listed. No ROS."""
import csv
import io
import json
import os
import shutil
import tarfile
import zipfile

import pytest

from course_grader import reports, rubric, similarity
from course_grader.similarity import LANGUAGES, Run

EXAMPLES = os.path.join(similarity.repository_root(), 'examples', 'grading')
CPP, PYTHON = LANGUAGES
# Neither the class's nor the hostile inputs' tests can compare without sim: Debian 13 does not
# carry it, and there the report must say so.
HAS_SIM = all(shutil.which(language.tool) for language in LANGUAGES)

# sim_c++ -n -e -s as it prints (similarity-tester 3.0.2), one run line with no match, one foreign.
SIM_OUTPUT = '''File s0f0.cpp: 211 tokens, 56 lines
File s1f0.cpp: 199 tokens, 41 lines
File s2f1.cpp: 1 token, 1 line
Total input: 3 files (3 new, 0 old), 411 tokens

s0f0.cpp: line 18-56                      |s1f0.cpp: line 6-41                  [199]

s1f1.cpp: line 20-28                      |s2f0.cpp: line 15-19                  [55]
alice.cpp: line 1-2 | bob.cpp: line 1-2 [30]
'''


def test_the_runs_and_sizes_sim_prints_are_read_and_nothing_else():
    assert similarity.parse_runs(SIM_OUTPUT) == [Run('s0f0.cpp', 18, 56, 's1f0.cpp', 6, 41, 199),
                                                 Run('s1f1.cpp', 20, 28, 's2f0.cpp', 15, 19, 55)]
    assert similarity.parse_tokens(SIM_OUTPUT) == {'s0f0.cpp': 211, 's1f0.cpp': 199, 's2f1.cpp': 1}
    assert similarity.parse_runs('') == [] and similarity.parse_tokens('Total input: 0 files') == {}


def test_a_run_against_the_given_material_takes_its_inner_lines_and_its_edges_only_when_given():
    lines = ['int x = 1;', 'a();', 'b();', '  c( ) ;', 'rate = 7;   // mine', 'd();', 'e();']
    given = {similarity.normal(line) for line in ['a();', 'c();', 'd();', 'rate = 10;']}
    runs = [Run('s0f0.cpp', 2, 5, 'g0.cpp', 1, 4, 20), Run('s0f0.cpp', 6, 6, 'g0.cpp', 9, 9, 12)]
    # 3 and 4 inside the first run; 2 (given) its first line; 5, the run's last line, is the
    # student's own (a changed constant): kept; 6 alone is a run of one given line.
    assert similarity.given_lines(runs, lines, given) == {2, 3, 4, 6}
    assert similarity.given_lines([], lines, given) == set()


def test_the_code_of_a_page_is_its_fenced_and_indented_blocks():
    page = 'Text about `x`.\n\n    rospy.init_node("a")\n    pub.publish(m)\n\n```cpp\nros::spin();\n```\nMore text.\n'
    assert similarity.markdown_code(page) == '    rospy.init_node("a")\n    pub.publish(m)\nros::spin();\n'


def test_the_given_material_of_each_lab_is_found_in_the_repository():
    for lab in similarity.GIVEN:
        given = similarity.given_texts(lab)
        assert len(given[PYTHON if lab == 'move_turtlebot3' else CPP]) >= 5, lab
    slide = open(os.path.join(similarity.repository_root(), 'tests', 'student', 'slides',
                              'my_turtle_node_stage2.cpp')).read()
    assert slide in similarity.given_texts('my_turtle')[CPP]


def test_a_submission_offers_its_source_files_only_bounded_and_never_through_a_link(tmp_path, monkeypatch):
    package = tmp_path / 'pkg'
    (package / 'src').mkdir(parents=True)
    (package / 'src' / 'node.cpp').write_text('int main() {}\n')
    (package / 'scripts').mkdir()
    (package / 'scripts' / 'evil\n\x1b[31mname.py').write_text('print(1)\n')
    (package / 'scripts' / 'binary.py').write_bytes(b'\x00\x01ELF')
    (package / 'scripts' / 'latin1.py').write_bytes('caf\xe9'.encode('latin-1'))
    (package / 'scripts' / 'huge.py').write_text('x = 1\n' * (similarity.MAX_FILE_BYTES // 6 + 1))
    (package / 'scripts' / 'notes.txt').write_text('not code\n')
    (package / 'scripts' / 'link.py').symlink_to(package / 'src' / 'node.cpp')
    (package / 'scripts' / 'passwd.py').symlink_to('/etc/passwd')
    (package / 'linked').symlink_to('/usr/lib/python3/dist-packages', target_is_directory=True)
    (package / 'build').mkdir()
    (package / 'build' / 'generated.cpp').write_text('int generated;\n')
    found = similarity.source_files(str(package))
    assert [(path, language.name) for path, language, _ in found] == [
        ('scripts/evil\n\x1b[31mname.py', 'Python'), ('src/node.cpp', 'C++')]
    many = tmp_path / 'many'
    many.mkdir()
    for number in range(similarity.MAX_FILES + 10):
        (many / ('f%03d.py' % number)).write_text('x = %d\n' % number)
    assert len(similarity.source_files(str(many))) == similarity.MAX_FILES
    monkeypatch.setattr(similarity, 'MAX_STUDENT_BYTES', 30)
    kept = [path for path, _, _ in similarity.source_files(str(many))]
    assert kept == ['f000.py', 'f001.py', 'f002.py', 'f003.py', 'f004.py']   # 6 bytes each


def test_the_report_and_the_csv_show_names_and_code_as_text(tmp_path):
    a = {'name': '=HYPERLINK("http://x")', 'id': '', 'folder': 'HYPERLINK'}
    b = {'name': 'bob <script>alert(1)</script>', 'id': '4711', 'folder': 'bob_4711'}
    code = ['if (a < b) {', '</pre><script>x()</script>', '    ros::spinOnce();']
    run = {'tokens': 30, 'a': {'path': 'src/<b>.cpp', 'first': 3, 'lines': code, 'given': [2]},
           'b': {'path': 'src/x\n\x1b.cpp', 'first': 9, 'lines': code, 'given': [2]}}
    result = {'pairs': [{'a': a, 'b': b, 'percent': 80, 'shared_lines': 2, 'runs': [run]}],
              'unread': [('<i>carol</i>', 'the archive holds "<x>" twice: refused')], 'error': None, 'given_files': 7}
    (tmp_path / similarity.RESULT_NAME).write_text(json.dumps(result))
    section = similarity.html_section(str(tmp_path))
    assert '<script>' not in section and '<b>' not in section and '<i>' not in section
    assert '&lt;/pre&gt;&lt;script&gt;x()&lt;/script&gt;' in section and 'bob &lt;script&gt;' in section
    assert '80 %' in section and 'lines 3-5' in section and 'lines 9-11' in section
    assert section.count('<span style="color:#999">    ros::spinOnce();</span>') == 2   # given: grey
    similarity.write_csv(result['pairs'], str(tmp_path / 'similarity.csv'))
    with open(str(tmp_path / 'similarity.csv'), encoding='utf-8') as stream:
        rows = list(csv.reader(stream))
    assert rows == [['student_a', 'id_a', 'student_b', 'id_b', 'percent', 'shared_lines'],
                    ['\'=HYPERLINK("http://x")', '', 'bob <script>alert(1)</script>', '4711', '80', '2']]
    assert similarity.html_section(str(tmp_path / 'no such folder')) == ''


def copy_student(lab, student, folder):
    """An example student's folder (examples/grading/LAB/STUDENT; model: the course's package) in folder."""
    target = os.path.join(str(folder), student)
    shutil.copytree(os.path.realpath(os.path.join(EXAMPLES, lab, student)), target)
    return target


def changed_copy(lab, folder, name, path, edits):
    """The model of the lab with edits [(old, new)] in its file path: a student's own changes."""
    target = os.path.join(str(folder), name)
    shutil.copytree(os.path.realpath(os.path.join(EXAMPLES, lab, 'model')), os.path.join(target, lab))
    file_path = os.path.join(target, lab, path)
    with open(file_path) as stream:
        text = stream.read()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    with open(file_path, 'w') as stream:
        stream.write(text)
    return target


# Two students' changed node: the same extra function and the same changed constants.
CLAMP = '''
// Keeps a speed within what the turtle may do, either way
double clampSpeed(double wanted, double limit)
{
    if (wanted > limit) {
        return limit;
    }
    if (wanted < -limit) {
        return -limit;
    }
    return wanted;
}

int main('''
MY_TURTLE_PAIR = [('\nint main(', CLAMP), ('msg.linear.x = lin_vel_;', 'msg.linear.x = clampSpeed(lin_vel_, 2.5);'),
                  ('msg.angular.z = ang_vel_;', 'msg.angular.z = clampSpeed(ang_vel_, 1.75);'),
                  ('ros::Rate rate(10);', 'ros::Rate rate(25);')]
RAMP = '''

def ramp_up(move, step, top_speed):
    """Speeds the robot up a little at each call, never above top_speed, and says so."""
    move.linear.x = min(top_speed, move.linear.x + step)
    rospy.loginfo('ramping up: %.2f m/s of %.2f', move.linear.x, top_speed)
    return move


def talker():'''
MOVE_TURTLEBOT3_PAIR = [('\n\ndef talker():', RAMP), ("number_param('~linear', 1.0)", "number_param('~linear', 0.35)"),
                        ('        pub.publish(move)', '        pub.publish(ramp_up(move, 0.05, 0.8))'),
                        ('rospy.Rate(1)', 'rospy.Rate(4)')]


@pytest.mark.parametrize('lab, path, edits, others', [
    ('my_turtle', 'src/my_turtle_node.cpp', MY_TURTLE_PAIR, ['model', 'slides_as_printed', 'forward_only', 'hostile']),
    ('move_turtlebot3', 'scripts/trajectory.py', MOVE_TURTLEBOT3_PAIR,
     ['model', 'slides_as_printed', 'no_chmod_early_stop', 'crash_hang_nostop', 'cmake_error', 'hostile'])])
def test_of_a_class_that_hands_in_the_slides_only_the_two_who_share_a_changed_node_are_listed(
        tmp_path, lab, path, edits, others):
    students = [copy_student(lab, student, tmp_path) for student in others]
    students.append(changed_copy(lab, tmp_path, 'dana', path, edits))
    students.append(changed_copy(lab, tmp_path, '=evan <b>', path, edits))
    out = tmp_path / 'out'
    out.mkdir()
    said = similarity.write_class(lab, lab, sorted(students), str(out))
    with open(str(out / 'similarity.csv'), encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    page = reports.html_report([], rubric.load(lab), str(out))
    if not HAS_SIM:
        assert said.startswith('similar submissions: not compared: sim_') and 'Debian 13 does not carry it' in said
        assert rows == [] and 'Debian 13 does not carry it' in page
        return
    assert said == ('similar submissions: 1 pair beyond the slides and the lab\'s pages (%s); sim ran on this machine, '
                    'not isolated' % (out / 'similarity.csv'))
    assert [(row['student_a'], row['student_b']) for row in rows] == [("'=evan <b>", 'dana')]
    assert int(rows[0]['percent']) >= 50 and int(rows[0]['shared_lines']) >= 5
    assert '<h2 id="similar-submissions">' in page and '=evan &lt;b&gt; and dana' in page
    assert ('clampSpeed' if lab == 'my_turtle' else 'ramp_up') in page


def test_without_the_given_material_nothing_is_compared_and_the_report_says_why(tmp_path, monkeypatch):
    monkeypatch.setattr(similarity, 'repository_root', lambda: str(tmp_path / 'installed'))
    out = tmp_path / 'out'
    out.mkdir()
    student = copy_student('my_turtle', 'model', tmp_path)
    said = similarity.write_class('my_turtle', 'my_turtle', [student], str(out))
    assert 'not compared: what every student of my_turtle is given was not found' in said
    said = similarity.write_class('my_own_lab', 'my_own_lab', [student], str(out))
    assert said == ('similar submissions: not compared: the material every student of my_own_lab is given is '
                    'not listed (GIVEN in course_grader/similarity.py)')
    assert open(str(out / 'similarity.csv')).read().strip() == 'student_a,id_a,student_b,id_b,percent,shared_lines'


def test_a_refused_archive_is_named_not_compared_and_an_archive_is_read_as_the_grader_reads_it(tmp_path):
    refused = str(tmp_path / 'mallory.tar.gz')
    with tarfile.open(refused, 'w:gz') as archive:
        member = tarfile.TarInfo('../../escaped.py')
        member.size = 4
        archive.addfile(member, io.BytesIO(b'x=1\n'))
    zipped = str(tmp_path / 'zoe.zip')
    with zipfile.ZipFile(zipped, 'w') as archive:
        archive.writestr('ws/src/my_turtle/package.xml', '<package><name>my_turtle</name></package>')
        archive.writestr('ws/src/my_turtle/src/node.cpp', 'int main() { return 0; }\n')
        archive.writestr('ws/src/other/helper.py', 'print(1)\n')   # not the lab's package: not read
    students, unread = similarity.class_sources([refused, zipped], 'my_turtle', str(tmp_path / 'scratch'))
    assert unread == [('mallory', "the archive holds '../../escaped.py', which points outside its folder: refused")]
    assert [(who.name, [(path, text) for path, _, text in files]) for who, files in students.items()] == [
        ('zoe', [('src/node.cpp', 'int main() { return 0; }\n')])]
    assert not os.path.exists(str(tmp_path / 'escaped.py'))
