#!/usr/bin/env python3
"""The shell commands of the slides, typed while move_turtle.launch runs, print what the slides show."""
import re
import subprocess
import unittest

import rostest

from course_testing.processes import PtyProgram
from course_common.waiting import wait_until


def shell(*command):
    """A command's standard output; fails the test with its error output if it fails."""
    result = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                            timeout=60)
    if result.returncode != 0:
        raise AssertionError('%s failed (%d): %s' % (' '.join(command), result.returncode,
                                                     result.stderr))
    return result.stdout


class SlideCommandsTest(unittest.TestCase):

    def topics(self):
        return shell('rostopic', 'list').split()

    def test_rostopic_list_shows_the_turtle_topics(self):
        # The slide also lists /rosout_agg, which roscore's rosout node publishes; rostest's
        # master runs no rosout node, so it is not expected here.
        for topic in ['/rosout', '/turtle1/cmd_vel', '/turtle1/color_sensor', '/turtle1/pose']:
            wait_until(lambda: topic in self.topics(), 30, '%s in `rostopic list`' % topic)

    def test_rostopic_info_pose(self):
        wait_until(lambda: '/turtle1/pose' in self.topics(), 30, '/turtle1/pose to appear')
        info = shell('rostopic', 'info', '/turtle1/pose')
        self.assertTrue(info.startswith('Type: turtlesim/Pose\n'), info)
        self.assertRegex(info, r'Publishers: \n \* /turtlesim_node \(http://localhost:\d+/\)\n')
        # Our final node listens to the pose, so here it is not "Subscribers: None" as on the slide.
        self.assertRegex(info, r'Subscribers: \n \* /my_turtle_node \(http://localhost:\d+/\)\n')

    def test_teleop_topic_while_the_keyboard_teleop_runs(self):
        teleop = PtyProgram(['roslaunch', 'turtlebot_teleop', 'keyboard_teleop.launch'])
        try:
            teleop.wait_for_output('Control Your Turtlebot!', timeout=30)
            wait_until(lambda: re.search(r'Publishers: \n \* /turtlebot_teleop_keyboard ',
                                         shell('rostopic', 'info', '/cmd_vel_mux/input/teleop')),
                       30, 'the teleop as publisher of /cmd_vel_mux/input/teleop')
            self.assertIn('/cmd_vel_mux/input/teleop', self.topics())
            info = shell('rostopic', 'info', '/cmd_vel_mux/input/teleop')
            self.assertTrue(info.startswith('Type: geometry_msgs/Twist\n'), info)
            self.assertRegex(info, r'Subscribers: \n \* /my_turtle_node ')
        finally:
            teleop.stop()

    def test_rosrun_of_a_launch_file_fails_as_the_readme_says(self):
        """The slide's `rosrun my_turtle move_turtle.launch` cannot work: rosrun runs executables."""
        result = subprocess.run(['rosrun', 'my_turtle', 'move_turtle.launch'],
                                stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("Couldn't find executable named move_turtle.launch", result.stdout)


if __name__ == '__main__':
    rostest.rosrun('my_turtle', 'slide_commands', SlideCommandsTest)
