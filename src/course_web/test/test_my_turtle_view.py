#!/usr/bin/env python3
"""The page beside the 000 lab's `roslaunch my_turtle move_turtle.launch`: it finds turtlesim under
the launch's node name (/turtlesim_node), and its arrows reach my_turtle_node's teleop relay
(cmd_vel_mux/input/teleop, where turtlebot_teleop publishes), which drives turtle1."""
import xmlrpc.client

import rosgraph
import rostest
from geometry_msgs.msg import Twist
from selenium.webdriver.common.keys import Keys

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from view_in_browser import ViewInBrowser

RELAY = '/cmd_vel_mux/input/teleop'


def publishes_to(publisher, topic, subscriber):
    """Whether node `publisher` has a connection on `topic` to node `subscriber` (its bus info)."""
    master = rosgraph.Master('/my_turtle_view_test')
    try:
        connections = xmlrpc.client.ServerProxy(master.lookupNode(publisher)).getBusInfo('/test')[2]
    except Exception:
        return False
    return any(c[1] == subscriber and c[2] == 'o' and c[4] == topic for c in connections)


class MyTurtleViewTest(ViewInBrowser):
    def test_arrows_drive_turtle1_through_the_relay(self):
        self.wait_shown('turtlesim')
        pose = TopicRecorder('/turtle1/pose', Pose)
        start = wait_until(pose.latest, 10, 'turtle1\'s pose')
        self.wait_page_shows_turtle_at(start)
        wait_until(lambda: publishes_to('/course_web', RELAY, '/my_turtle_node'), 30,
                   'my_turtle_node to listen to the view on %s' % RELAY, poll=0.2)
        teleop = TopicRecorder(RELAY, Twist)
        # Connected to the view before the key: a command sent before would not be recorded.
        wait_until(lambda: teleop.subscriber.get_num_connections() > 0, 30,
                   'the test to listen to the view on %s' % RELAY, poll=0.2)
        heard = teleop.count()
        self.press(Keys.ARROW_UP)   # one command a key: it may arrive before press() returns
        teleop.wait_for_count(heard + 1, timeout=10)
        command = teleop.messages()[heard]
        self.assertEqual((command.linear.x, command.angular.z), (2.0, 0.0))
        moved = pose.wait_for(lambda p: p.x > start.x + 0.5, 10, 'the relay to drive turtle1 forward')
        self.assertAlmostEqual(moved.y, start.y, places=3)
        # Where it comes to rest (the relay's last command timed out, or the wall): while it moves, the
        # page may already be past any pose read here.
        def at_rest():
            last_two = pose.messages(max(0, pose.count() - 2))
            return (len(last_two) == 2 and last_two[0].x == last_two[1].x > moved.x) and last_two[1]
        stopped = wait_until(at_rest, 20, 'turtle1 to come to rest')
        self.wait_page_shows_turtle_at(stopped)


if __name__ == '__main__':
    rostest.rosrun('course_web', 'my_turtle_view', MyTurtleViewTest)
