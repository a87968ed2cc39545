"""course_testing.pictures: one folder per test under ROS_HOME, emptied at each start."""
import os

from course_testing.pictures import picture_folder


def test_a_tests_folder_is_under_ros_home_and_starts_empty(tmp_path, monkeypatch):
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    folder = picture_folder('fake_tb3', 'wander')
    assert folder == os.path.join(str(tmp_path), 'test_pictures', 'fake_tb3', 'wander')
    with open(os.path.join(folder, 'wander.png'), 'wb') as stream:
        stream.write(b'last run')
    other = picture_folder('turtlesim', 'wander')
    assert picture_folder('fake_tb3', 'wander') == folder
    assert os.listdir(folder) == []
    assert os.path.isdir(other)   # another package's test of the same name keeps its own
