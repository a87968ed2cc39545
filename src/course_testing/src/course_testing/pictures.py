"""Where a test keeps what it drew or screenshot, for a person to look at after the run."""
import os
import shutil

import rospkg


def picture_folder(package, test):
    """The folder of one test's pictures (and the logs that go with them): test_pictures/PACKAGE/TEST
    in ROS_HOME (./test.sh gives its steps build/test_logs/ros_home), emptied when the test starts,
    so that one run's pictures replace the last instead of piling up in /tmp."""
    folder = os.path.join(rospkg.get_ros_home(), 'test_pictures', package, test)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    return folder
