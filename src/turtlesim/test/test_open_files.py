#!/usr/bin/env python3
"""turtlesim under a low open-file limit (ulimit -n 256, soft and hard): turtles hold no open file,
kills give back what the turtle held, a spawn at the limit gets a clear error and leaves nothing
behind, and the node keeps serving the other turtles a pose every tick."""
import os
import resource
import subprocess
import tempfile
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist

from course_common.processes import stop_process_group
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.holdings import FILE_RESERVE
from turtlesim.msg import Pose
from turtlesim.srv import Kill, Spawn, TeleportAbsolute
from turtlesim.world import TICK_SECONDS
from turtlesim_testing import graph

FILE_LIMIT = 256
TURTLES_BEYOND_THE_LIMIT = 400  # three open files each before: the old node stopped at about 80
CONNECTIONS_UNDER_WAY = 8  # at most, while the next turtle is spawned: well within FILE_RESERVE


def low_file_limit():
    resource.setrlimit(resource.RLIMIT_NOFILE, (FILE_LIMIT, FILE_LIMIT))


def names_under(prefix, node='/turtlesim'):
    """The topic and service names under prefix that the master knows from turtlesim (it publishes,
    subscribes or serves them)."""
    return sorted(name for entries in graph() for name, nodes in entries.items()
                  if name.startswith(prefix) and node in nodes)


class OpenFilesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('open_files_test')
        cls.output = tempfile.NamedTemporaryFile('w+', prefix='turtlesim_', suffix='.log')
        cls.node = subprocess.Popen(['rosrun', 'turtlesim', 'turtlesim_node'], stdout=cls.output,
                                    stderr=subprocess.STDOUT, start_new_session=True, preexec_fn=low_file_limit,
                                    env=dict(os.environ, DISPLAY=''))
        rospy.wait_for_service('/spawn', 30.0)
        rospy.wait_for_service('/kill', 30.0)
        uri = rosgraph.Master('/open_files_test').lookupNode('/turtlesim')
        cls.pid = xmlrpc.client.ServerProxy(uri).getPid('/open_files_test')[2]
        cls.spawn = rospy.ServiceProxy('/spawn', Spawn)
        cls.kill = rospy.ServiceProxy('/kill', Kill)

    @classmethod
    def tearDownClass(cls):
        stop_process_group(cls.node)
        cls.output.close()

    def open_files(self):
        return len(os.listdir('/proc/%d/fd' % self.pid))

    def node_output(self):
        with open(self.output.name) as log:
            return log.read()

    @staticmethod
    def pose_timing(poses, count=190):
        """(median gap in ms, mean rate in Hz) of the next `count` poses."""
        start = poses.count()
        wait_until(lambda: poses.count() - start >= count, 10.0, '%d poses of turtle1' % count)
        times = [arrival for arrival, _ in poses.entries(start)]
        gaps = sorted(later - earlier for earlier, later in zip(times, times[1:]))
        return 1000.0 * gaps[len(gaps) // 2], (len(times) - 1) / (times[-1] - times[0])

    def test_the_node_runs_under_the_limit_and_says_what_it_holds(self):
        with open('/proc/%d/limits' % self.pid) as limits:
            line = next(line for line in limits if line.startswith('Max open files'))
        self.assertEqual(line.split()[3:5], [str(FILE_LIMIT), str(FILE_LIMIT)])
        wait_until(lambda: 'Open-file limit %d: a turtle holds no open file' % FILE_LIMIT in self.node_output(),
                   10.0, 'the start-up line about the open-file limit')

    def test_turtles_hold_no_open_file_and_kills_leave_nothing(self):
        before = self.open_files()
        names = ['many%d' % number for number in range(TURTLES_BEYOND_THE_LIMIT)]
        for name in names:
            self.assertEqual(self.spawn(1.0, 1.0, 0.0, name).name, name)
        # a registration with the master may still hold its socket for a moment
        self.assertLessEqual(self.open_files(), before + 2)
        self.assertEqual(len(names_under('/many399/')), 6)
        for name in names:
            self.kill(name)
        self.assertLessEqual(self.open_files(), before + 2)
        self.assertEqual(names_under('/many'), [])
        self.assertEqual(self.spawn(2.0, 2.0, 0.0, 'many0').name, 'many0')
        self.kill('many0')

    def test_a_spawn_at_the_limit_gets_a_clear_error_and_the_node_keeps_serving(self):
        poses = TopicRecorder('/turtle1/pose', Pose)
        self.addCleanup(poses.close)
        poses.next_message(10.0)
        before = self.open_files()
        # Fill the node's files with connections: a publisher here on each new turtle's cmd_vel is
        # one socket in the node (and no traffic), until a spawn is refused. The next spawn goes
        # while the last few connections are still being made (a fifth of the time of one by one),
        # never more than fit in the node's reserve.
        drivers, refusal = [], None
        self.addCleanup(lambda: [driver.unregister() for driver in drivers])

        def unconnected():
            return sum(driver.get_num_connections() == 0 for driver in drivers)
        for number in range(FILE_LIMIT):
            wait_until(lambda: unconnected() < CONNECTIONS_UNDER_WAY, 10.0,
                       'turtlesim on the cmd_vel of all but %d new turtles' % (CONNECTIONS_UNDER_WAY - 1))
            name = 'full%d' % number
            try:
                self.spawn(1.0, 1.0, 0.0, name)
            except rospy.ServiceException as error:
                refusal, refused_name = str(error), name
                break
            drivers.append(rospy.Publisher('/%s/cmd_vel' % name, Twist, queue_size=1))
        self.assertIsNotNone(refusal, 'no spawn refused with %d connections' % len(drivers))
        wait_until(lambda: unconnected() == 0, 10.0, "turtlesim on every new turtle's cmd_vel")
        at_limit = self.open_files()
        self.assertGreater(at_limit, FILE_LIMIT - FILE_RESERVE - 5)
        self.assertLess(at_limit, FILE_LIMIT)
        self.assertIn('Cannot spawn turtle [%s]: turtlesim has ' % refused_name, refusal)
        self.assertIn('of its %d open files in use (ulimit -n)' % FILE_LIMIT, refusal)
        def refusal_lines():
            return [line for line in self.node_output().splitlines()
                    if line.startswith('[ERROR]') and 'Cannot spawn turtle [%s]' % refused_name in line]
        logged = wait_until(refusal_lines, 10.0, 'the refusal in the log')
        self.assertIn(logged[0].split(']: ', 1)[1], refusal, 'the log line and the service error say the same')
        # nothing of the refused turtle exists
        self.assertEqual(names_under('/%s/' % refused_name), [])
        with self.assertRaises(rospy.ServiceException):
            self.kill(refused_name)

        # the other turtles are served as before: a service of a turtle answers, a pose comes every tick
        rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(3.0, 4.0, 0.0)
        wait_until(lambda: (poses.latest().x, poses.latest().y) == (3.0, 4.0), 5.0, 'turtle1 at (3, 4)')
        # A tick every TICK_SECONDS and none held up by the full node. The exact mean rate is the
        # interface test's and the bench's: on a busy shared machine a few ticks come late and are skipped.
        median_gap, rate = self.pose_timing(poses)
        self.assertAlmostEqual(median_gap, TICK_SECONDS * 1000, delta=1.0)
        self.assertGreater(rate, 0.9 / TICK_SECONDS)

        # kills give the connections back, and a spawn works again
        for driver, number in zip(drivers[:10], range(10)):
            self.kill('full%d' % number)
        wait_until(lambda: self.open_files() <= at_limit - 10, 10.0,
                   'the node to close the connections of 10 killed turtles (%d files)' % at_limit)
        self.assertEqual(self.spawn(1.0, 1.0, 0.0, refused_name).name, refused_name)
        self.assertEqual(len(names_under('/%s/' % refused_name)), 6)
        self.kill(refused_name)
        for number in range(10, len(drivers)):
            self.kill('full%d' % number)
        # every connection closed; a few sockets the node opened meanwhile may stay (rosout, the master)
        wait_until(lambda: self.open_files() <= at_limit - len(drivers) + 3, 10.0,
                   'the node to close the connections of all %d killed turtles (%d files, %d at first)'
                   % (len(drivers), at_limit, before))
        self.assertEqual(names_under('/full'), [])


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'open_files', OpenFilesTest)
