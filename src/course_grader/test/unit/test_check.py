"""The student's check refuses, in one sentence and exit status 2, what it cannot check; Ctrl-C ends
it in one sentence too."""
import os

from course_grader import check

EXAMPLES = os.path.join(os.path.dirname(__file__), '..', '..', '..', '..', 'examples', 'grading')


def test_a_folder_without_package_xml_is_not_a_package(tmp_path, capsys):
    assert check.main(['my_turtle', str(tmp_path)]) == 2
    assert 'is not a package: it has no package.xml' in capsys.readouterr().err


def test_a_package_of_another_name_is_named(capsys):
    assert check.main(['my_turtle', os.path.join(EXAMPLES, 'move_turtlebot3', 'model')]) == 2
    assert 'is the package move_turtlebot3, not my_turtle' in capsys.readouterr().err


def test_an_unknown_criterion_lists_the_known_ones(capsys):
    assert check.main(['my_turtle', os.path.join(EXAMPLES, 'my_turtle', 'model'), '--only', 'nope']) == 2
    assert 'its criteria are builds, launch, teleop, prints_pose' in capsys.readouterr().err


def test_an_unknown_lab_lists_the_labs(capsys):
    assert check.main(['nolab']) == 2
    assert 'there is no lab nolab; the labs are move_turtlebot3, my_turtle, ros_exercises' in capsys.readouterr().err


def test_ctrl_c_ends_the_check_in_one_sentence_and_exit_130(tmp_path, monkeypatch, capsys):
    def interrupted(self, path):
        raise KeyboardInterrupt
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    monkeypatch.setattr(check, 'exit_on_terminate', lambda: None)   # the test process's own signals stay
    monkeypatch.setattr(check.Grader, 'grade_one', interrupted)
    assert check.main(['my_turtle', os.path.join(EXAMPLES, 'my_turtle', 'model')]) == 130
    assert capsys.readouterr().err == ('check: stopped (Ctrl-C) before the end: nothing was checked, your last '
                                       'check is still the one shown\n')
    assert os.listdir(str(tmp_path / 'course_check' / 'my_turtle')) == []   # no half check kept
