#!/usr/bin/env python3
"""rostest: turtlebot3_gazebo_rviz under Xvfb shows the laser scan as red points.

The launch file comes from the package named by the private parameter `launch_package` (default
fake_tb3; turtlebot3_gazebo for the slides' command). Starts its own Xvfb (on a display it picks
free), runs the rviz launch file against the test's master, screenshots the screen with
`import -window root` until red points show, and stops everything it started. rviz is started once
more if a signal killed it before it drew (course_testing.rviz); the test's log says so.
"""
import os
import unittest

import rospy
import rostest

from course_testing.pictures import picture_folder
from course_testing.processes import LoggedLaunch
from course_testing.rviz import rviz_until_drawn
from course_testing.screen import VirtualScreen, red_pixels


class RvizTest(unittest.TestCase):
    def test_rviz_shows_the_scan_in_red(self):
        rospy.init_node('rviz_test')
        package = rospy.get_param('~launch_package', 'fake_tb3')
        folder = picture_folder(package, rospy.get_name().lstrip('/'))
        screenshot = os.path.join(folder, 'rviz.png')
        starts = []

        def start():
            starts.append(LoggedLaunch(['roslaunch', package, 'turtlebot3_gazebo_rviz.launch'],
                                       os.path.join(folder, 'rviz-launch-%d.log' % len(starts)),
                                       screen.environment()))
            return starts[-1]

        with VirtualScreen() as screen:
            self.assertEqual(red_pixels(screen.screenshot(screenshot)), 0)  # an empty screen has no red
            rviz, notes = rviz_until_drawn(start, LoggedLaunch.stop, screen, screenshot, red_at_least=100)
            try:
                for note in notes:
                    rospy.logwarn(note)
                rospy.loginfo('rviz: %d red pixels, screenshot %s', red_pixels(screenshot), screenshot)
                self.assertIsNotNone(rospy.get_param('/robot_description', None))
            finally:
                rviz.stop()


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'rviz_screen', RvizTest)
