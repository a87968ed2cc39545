#!/usr/bin/env python3
"""rostest: turtlebot3_gazebo_rviz under Xvfb shows the laser scan as red points.

The launch file comes from the package named by the private parameter `launch_package` (default
fake_tb3; turtlebot3_gazebo for the slides' command). Starts its own Xvfb (on a display it picks
free), runs the rviz launch file against the test's master, screenshots the screen with
`import -window root` until red points show, and stops everything it started.
"""
import os
import signal
import subprocess
import tempfile
import unittest

import numpy as np
import rospy
import rostest
from PIL import Image

from course_common.testing import wait_until


def start_xvfb():
    """An Xvfb on a free display: (process, ':N')."""
    read_end, write_end = os.pipe()
    xvfb = subprocess.Popen(['Xvfb', '-displayfd', str(write_end), '-screen', '0', '1280x1024x24',
                             '-nolisten', 'tcp'], pass_fds=(write_end,), stderr=subprocess.DEVNULL)
    os.close(write_end)
    with os.fdopen(read_end) as stream:
        number = stream.readline().strip()
    if not number:
        raise AssertionError('Xvfb did not start')
    return xvfb, ':' + number


def stop(process):
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGINT)
        try:
            process.wait(15)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


def red_points(display, path):
    """Pixels of the screen that are laser red."""
    subprocess.run(['import', '-display', display, '-window', 'root', path], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30)
    image = np.asarray(Image.open(path).convert('RGB')).astype(int)
    return int(np.sum((image[:, :, 0] > 200) & (image[:, :, 1] < 60) & (image[:, :, 2] < 60)))


class RvizTest(unittest.TestCase):
    def test_rviz_shows_the_scan_in_red(self):
        rospy.init_node('rviz_test')
        package = rospy.get_param('~launch_package', 'fake_tb3')
        xvfb, display = start_xvfb()
        screenshot = os.path.join(tempfile.mkdtemp(), 'rviz.png')
        rviz = subprocess.Popen(['roslaunch', package, 'turtlebot3_gazebo_rviz.launch'],
                                env=dict(os.environ, DISPLAY=display), start_new_session=True,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            before = red_points(display, screenshot)
            self.assertEqual(before, 0)  # an empty screen has no red
            count = wait_until(lambda: red_points(display, screenshot) > 100, 90,
                               'red laser points on the rviz screen')
            self.assertTrue(count)
            rospy.loginfo('rviz: %d red pixels, screenshot %s', red_points(display, screenshot),
                          screenshot)
            self.assertIsNotNone(rospy.get_param('/robot_description', None))
        finally:
            stop(rviz)
            xvfb.terminate()
            xvfb.wait(10)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'rviz_screen', RvizTest)
