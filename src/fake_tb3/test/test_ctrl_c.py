#!/usr/bin/env python3
"""rostest: on Ctrl-C fake_tb3 stops its simulation, writes its picture, and only then leaves the ROS
graph: whoever waits for it to leave (the grader, which then ends it at once) has the picture."""
import os
import signal
import subprocess
import unittest

import rosgraph
import rospy
import rostest
from nav_msgs.msg import Odometry

from course_common.processes import stop_process_group
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from course_testing.pictures import picture_folder

NAME = '/ctrl_c_fake_tb3'


def registered():
    publishers, subscribers, services = rosgraph.Master('/ctrl_c_test').getSystemState()
    return any(NAME in nodes for _, nodes in publishers + subscribers + services)


class CtrlCTest(unittest.TestCase):

    def test_the_picture_is_written_before_the_node_leaves_the_graph(self):
        rospy.init_node('ctrl_c_test')
        picture = os.path.join(picture_folder('fake_tb3', 'ctrl_c'), 'at_ctrl_c.png')
        odom = TopicRecorder('/odom', Odometry)
        simulator = subprocess.Popen(['rosrun', 'fake_tb3', 'fake_tb3_node', '__name:=' + NAME.lstrip('/'),
                                      '_picture_png:=' + picture],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
                                     universal_newlines=True)
        try:
            odom.wait_for_count(3, timeout=60)
            os.killpg(simulator.pid, signal.SIGINT)
            wait_until(lambda: not registered(), 30, 'fake_tb3 to leave the graph')
            self.assertTrue(os.path.exists(picture))
            self.assertEqual(simulator.wait(30), 0)
            self.assertIn('fake_tb3: picture written to %s' % picture, simulator.stdout.read())
        finally:
            odom.close()
            stop_process_group(simulator)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'ctrl_c', CtrlCTest)
