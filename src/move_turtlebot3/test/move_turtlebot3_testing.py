"""Test helpers: run this package's launch files (as a student would, with roslaunch) against the
test's master, and watch the simulated robot through fake_tb3's topics."""
import time
import unittest

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

from course_checks import launch
from course_checks.robot import RobotWatch
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until

REPUBLISH_SECONDS = 0.5  # a lone node's scan sent again after this long without an answer


class Launch(launch.Launch):
    """roslaunch of one of this package's launch files (or a lone node), output collected."""

    def __init__(self, *argv):
        super().__init__(argv)

    def wait_for_output(self, text, timeout):
        return wait_until(lambda: text in self.output, timeout, what='%r in the output' % text)

    @classmethod
    def package_file(cls, launch_file, **args):
        return cls('roslaunch', 'move_turtlebot3', launch_file,
                   *['%s:=%s' % item for item in sorted(args.items())])


class Watch(RobotWatch):
    """The checks' RobotWatch, with waits that fail the test with a sentence on time-out."""

    def wait_until_running(self, timeout=60):
        wait_until(self.running, timeout, what='odom, scan and collisions from fake_tb3')

    def wait_for_command(self, timeout=60):
        """The node's first command heard: on a busy machine its start (python3, rospy) can take
        longer than a window of simulated time measured from the simulator's start (2 s at 10x)."""
        wait_until(lambda: self.copy('commands'), timeout, what='a command on /cmd_vel')

    def wait_sim_seconds(self, seconds, timeout):
        end = self.now() + seconds
        wait_until(lambda: self.now() >= end, timeout, what='%.0f simulated seconds' % seconds)


class LabTestCase(unittest.TestCase):
    """A test case with a RobotWatch, and a Launch (self.launch) stopped at its end."""

    def setUp(self):
        self.watch = Watch()
        self.launch = None

    def lock_step(self):
        """The next fake_tb3 holds simulated time after each scan until a cmd_vel answers it (a
        parameter the launch files leave alone, as the grader sets it): a node that answers each
        scan then drives the same at any real-time factor and load."""
        rospy.set_param('/fake_tb3/lock_step', True)
        self.addCleanup(rospy.delete_param, '/fake_tb3/lock_step')

    def tearDown(self):
        if self.launch is not None:
            self.launch.stop()
            # Kept in the test's log (and in the result file), to see what went on when it fails.
            print('--- output of %s:\n%s' % (self._testMethodName, self.launch.output))
        self.watch.close()


class LoneNode:
    """One of this package's scan nodes run alone, on scans and commands topics of the test's own."""

    def __init__(self, script):
        self.launch = Launch('rosrun', 'move_turtlebot3', script,
                             '/scan:=/odd_scan', '/cmd_vel:=/odd_cmd_vel')
        self._publisher = rospy.Publisher('/odd_scan', LaserScan, queue_size=1)
        self.commands = TopicRecorder('/odd_cmd_vel', Twist)
        wait_until(lambda: self._publisher.get_num_connections() > 0
                   and self.commands.subscriber.get_num_connections() > 0,
                   timeout=30, what='%s to connect' % script)

    def answer_to(self, scan):
        """Publish one scan and return the (linear, angular) command the node answers with."""
        count = self.commands.count()
        published = []

        def answered():
            if self.commands.count() > count:
                return True
            # (Again every half a second: the node's first answers can leave before its publisher
            # has taken in our fresh connection.)
            if not published or time.monotonic() - published[-1] >= REPUBLISH_SECONDS:
                self._publisher.publish(scan)
                published.append(time.monotonic())
            return False

        wait_until(answered, timeout=10, what='an answer to a scan')
        answer = self.commands.latest()
        return answer.linear.x, answer.angular.z

    @property
    def output(self):
        return self.launch.output

    def stop(self):
        self.commands.close()
        self._publisher.unregister()
        self.launch.stop()
