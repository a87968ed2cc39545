#!/usr/bin/env python3
"""The grader's recording of a run (course_checks.robot.RobotWatch) heard late: each scan handed on
2 ms after it came, as when the grader's receiving thread waits for the processor. Once the publisher
has ended, drain() waits until every scan it sent is recorded: the move_turtlebot3 lab compares the
scans a node printed with them (laser_data.py at 10x prints the last ones just before the stop)."""
import subprocess
import sys
import time
import unittest
from unittest import mock

import rospy
import rostest

from course_checks.robot import RobotWatch
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until

SCANS = 500
# A node of the test's: it waits for a subscriber on /scan, sends SCANS numbered scans at once
# (each publish() writes it out) and exits.
PUBLISHER = """
import rospy
from sensor_msgs.msg import LaserScan
rospy.init_node('scan_burst')
publisher = rospy.Publisher('/scan', LaserScan, queue_size=None)
while publisher.get_num_connections() == 0:
    rospy.sleep(0.01)
for number in range(%d):
    publisher.publish(LaserScan(range_max=3.5, ranges=[float(number)] * 360))
""" % SCANS


class LateRecorder(TopicRecorder):
    def _keep(self, message):
        time.sleep(0.002)   # the delay the test adds, not a wait
        super()._keep(message)


class LateHearingTest(unittest.TestCase):

    def test_every_scan_sent_before_the_publisher_ended_is_recorded(self):
        rospy.init_node('late_hearing_test')
        with mock.patch('course_checks.robot.TopicRecorder', LateRecorder):
            watch = RobotWatch()
        burst = subprocess.Popen([sys.executable, '-c', PUBLISHER])
        wait_until(lambda: burst.poll() is not None, 60, 'the scans to be sent')
        self.assertEqual(burst.returncode, 0)
        self.assertTrue(watch.drain(30))
        watch.close()
        scans = watch.copy('scans')
        self.assertEqual([scan.ranges[0] for scan in scans], [float(number) for number in range(SCANS)])


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'late_hearing', LateHearingTest)
