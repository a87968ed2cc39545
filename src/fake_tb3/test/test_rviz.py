#!/usr/bin/env python3
"""rostest: turtlebot3_gazebo_rviz under Xvfb shows the laser scan as red points.

The launch file comes from the package named by the private parameter `launch_package` (default
fake_tb3; turtlebot3_gazebo for the slides' command). Starts its own Xvfb (on a display it picks
free), runs the rviz launch file against the test's master, screenshots the screen with
`import -window root` until red points show, and stops everything it started.
"""
import os
import subprocess
import tempfile
import unittest

import rospy
import rostest

from course_common.processes import stop_process_group
from course_testing.screen import VirtualScreen, red_pixels
from course_common.waiting import wait_until


def red_points(screen, path):
    """Pixels of the screen that are laser red."""
    return red_pixels(screen.screenshot(path))


class RvizTest(unittest.TestCase):
    def test_rviz_shows_the_scan_in_red(self):
        rospy.init_node('rviz_test')
        package = rospy.get_param('~launch_package', 'fake_tb3')
        screenshot = os.path.join(tempfile.mkdtemp(), 'rviz.png')
        with VirtualScreen() as screen:
            self.assertEqual(red_points(screen, screenshot), 0)  # an empty screen has no red
            rviz = subprocess.Popen(['roslaunch', package, 'turtlebot3_gazebo_rviz.launch'],
                                    env=screen.environment(), start_new_session=True,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            try:
                # A screenshot costs a tenth of a second of CPU: taken back to back they starve
                # rviz's software rendering on a busy machine, so twice a second.
                wait_until(lambda: red_points(screen, screenshot) > 100, 90,
                           'red laser points on the rviz screen', poll=0.5)
                rospy.loginfo('rviz: %d red pixels, screenshot %s', red_points(screen, screenshot),
                              screenshot)
                self.assertIsNotNone(rospy.get_param('/robot_description', None))
            finally:
                stop_process_group(rviz)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'rviz_screen', RvizTest)
