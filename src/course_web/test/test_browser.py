#!/usr/bin/env python3
"""The page in a real browser (headless chromium), beside turtlesim and fake_tb3 in turtlebot3_world:
what it draws is where the simulators say (turtles with heading and name, trails, pen off, spawn,
kill, clear; the robot, its laser points, its path, its closest range), its keys drive them, it
follows a restarted turtlesim and fake_tb3, lets the simulators go when no page is left, and
Ctrl-C leaves no port behind."""
import math
import os
import re
import subprocess

import numpy as np
import rosgraph
import rospy
import rostest
from nav_msgs.msg import Odometry
from PIL import Image
from sensor_msgs.msg import LaserScan
from selenium.webdriver.common.keys import Keys
from std_srvs.srv import Empty, Trigger

from course_testing.browser import save_pixels
from course_common.processes import port_open, stop_process_group
from course_common.topic_recorder import TopicRecorder
from course_common.waiting import poll_until, wait_until
from turtlesim.msg import Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute
from turtlesim.world import TICK_SECONDS
from view_in_browser import TS_BACKGROUND, ViewInBrowser, near_colour, ts_pixel

RED = np.array([255, 0, 0])
LASER_RED = np.array([230, 20, 20])
HEAD_GREEN = (150, 200, 110)  # the turtle's head and feet, as the page draws them
PEN_WIDTH = 4


def printed_near(text, x, y, tolerance):
    """Whether the page's pose line, `x X m, y Y m, ...`, names a place within tolerance of (x, y)."""
    found = re.match(r'x (-?[0-9.]+) m, y (-?[0-9.]+) m', text or '')
    return bool(found) and abs(float(found.group(1)) - x) <= tolerance and abs(float(found.group(2)) - y) <= tolerance


def dark_pixels(pixels, col, row, half_width, half_height):
    """How many near-black pixels (the page's turtle names) a box centred there holds."""
    box = pixels[row - half_height:row + half_height + 1, col - half_width:col + half_width + 1]
    return int((box.astype(int).sum(axis=2) < 150).sum())


class BrowserTest(ViewInBrowser):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.pose = TopicRecorder('/turtle1/pose', Pose)
        cls.odom = TopicRecorder('/odom', Odometry)
        cls.scan = TopicRecorder('/scan', LaserScan)

    def still_turtle(self):
        def still():
            pose = self.pose.latest()
            return pose if pose is not None and pose.linear_velocity == 0 and pose.angular_velocity == 0 else None
        return wait_until(still, 20, 'turtle1 to stand still', poll=0.05)

    def wait_canvas(self, condition, what):
        """The turtlesim canvas of the page once condition(pixels) holds."""
        def shown():
            pixels = self.canvas('turtlesim')
            return condition(pixels) and [pixels]
        return wait_until(shown, 20, what, poll=0.1)[0]

    def test_1_turtlesim_turtle_trail_and_keys(self):
        self.wait_shown('turtlesim')
        rospy.wait_for_service('/turtle1/set_pen', 10)
        set_pen = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
        teleport = rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)
        set_pen(255, 0, 0, PEN_WIDTH, 0)
        teleport(2.0, 3.0, 0.0)
        self.pose.wait_for(lambda pose: abs(pose.x - 2.0) < 1e-4, 10, 'the teleport')  # maybe the first pose
        start = self.still_turtle()
        self.press(Keys.ARROW_UP)  # turtle_teleop_key: 2 m/s for 1 s, along +x
        wait_until(lambda: self.pose.latest().x > start.x + 0.5, 20, 'the arrow key to move turtle1', poll=0.02)
        end = self.still_turtle()
        self.assertAlmostEqual(end.x - start.x, 2.0 * 63 * TICK_SECONDS, delta=0.1)
        self.assertAlmostEqual(end.y, start.y, places=3)
        self.wait_page_shows_turtle_at(end)
        pixels = self.canvas('turtlesim')
        save_pixels(pixels, os.path.join(self.shots, 'course_web-turtlesim.png'))
        self.assertEqual(pixels.shape, (500, 500, 3))
        # The trail: red from the start to behind the turtle, background beside it.
        trail = []
        for fraction in (0.3, 0.5, 0.7):
            col, row = ts_pixel(start.x + fraction * (end.x - start.x), start.y)
            trail.append((col, row))
            self.assertTrue(near_colour(pixels, col, row, RED, radius=0), (col, row, pixels[row, col]))
            self.assertTrue(near_colour(pixels, col, row + 6, TS_BACKGROUND, radius=0), pixels[row + 6, col])
        # The teleport's line, from the centre to (2, 3), is there too.
        col, row = ts_pixel((5.544445 + 2.0) / 2, (5.544445 + 3.0) / 2)
        self.assertTrue(near_colour(pixels, col, row, RED, radius=1), pixels[row - 1:row + 2, col - 1:col + 2])
        # The turtle: its shell (neither background nor pen) where the simulator says it is, its
        # head ahead of it (theta 0: to the right), its name under it.
        col, row = ts_pixel(end.x, end.y)
        centre = pixels[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3).astype(int)
        self.assertFalse(any((abs(p - TS_BACKGROUND).sum() < 30 or abs(p - RED).sum() < 30) for p in centre), centre)
        self.assertTrue(near_colour(pixels, col + 13, row, HEAD_GREEN, radius=1), pixels[row, col + 13])
        self.assertGreater(dark_pixels(pixels, col, row + 33, 22, 6), 15, 'no name under turtle1')
        # Everywhere away from the turtle (and its name below it), the page has turtlesim's own pixels.
        saved = rospy.ServiceProxy('/turtlesim/save_canvas', Trigger)()
        self.assertTrue(saved.success, saved.message)
        original = np.array(Image.open(saved.message).convert('RGB'))
        mask = np.ones((500, 500), bool)
        mask[max(0, row - 25):row + 45, max(0, col - 40):col + 40] = False
        same = (np.abs(original.astype(int) - pixels.astype(int)).sum(axis=2) <= 3)[mask].mean()
        self.assertGreater(same, 0.999, 'page and turtlesim differ in %.3f %% of the pixels' % (100 * (1 - same)))
        # Left arrow: turns turtle1 by +2 rad/s for 1 s; the page turns its head with it.
        self.press(Keys.ARROW_LEFT)
        wait_until(lambda: self.pose.latest().theta > 0.5, 20, 'the left arrow to turn turtle1', poll=0.02)
        theta = self.still_turtle().theta
        head = (int(round(col + 13.5 * math.cos(theta))), int(round(row - 13.5 * math.sin(theta))))
        self.wait_canvas(lambda p: near_colour(p, head[0], head[1], HEAD_GREEN, radius=1)
                         and near_colour(p, col + 14, row, TS_BACKGROUND, radius=0),
                         'the page to turn turtle1\'s head to theta = %.2f' % theta)
        # Pen off: a teleport leaves no line.
        set_pen(255, 0, 0, PEN_WIDTH, 1)
        teleport(end.x, end.y + 3.0, 0.0)
        moved = wait_until(lambda: self.pose.latest().y > end.y + 2.9 and self.pose.latest(), 10, 'the teleport')
        self.wait_page_shows_turtle_at(moved)
        self.wait_canvas(lambda p: near_colour(p, *ts_pixel(end.x, end.y + 1.5), TS_BACKGROUND, radius=0)
                         and not near_colour(p, *ts_pixel(end.x, end.y + 3.0), TS_BACKGROUND, radius=0),
                         'turtle1 at its new place with no line to it')
        # A spawned turtle appears with its name, a killed one goes; clear wipes the trails.
        spot = ts_pixel(8.0, 8.0)
        rospy.ServiceProxy('/spawn', Spawn)(8.0, 8.0, 1.0, 'second')
        self.wait_canvas(lambda p: not near_colour(p, spot[0], spot[1], TS_BACKGROUND, radius=0)
                         and dark_pixels(p, spot[0], spot[1] + 33, 22, 6) > 15, 'the page to show turtle "second"')
        rospy.ServiceProxy('/kill', Kill)('second')
        self.wait_canvas(lambda p: near_colour(p, spot[0], spot[1], TS_BACKGROUND, radius=0)
                         and dark_pixels(p, spot[0], spot[1] + 33, 22, 6) == 0, 'the page to drop turtle "second"')
        self.assertTrue(near_colour(self.canvas('turtlesim'), *trail[1], RED, radius=0))
        rospy.ServiceProxy('/clear', Empty)()
        self.wait_canvas(lambda p: all(near_colour(p, c, r, TS_BACKGROUND, radius=0) for c, r in trail),
                         'clear to wipe the trail on the page')

    def test_2_fake_tb3_robot_scan_path_and_keys(self):
        self.wait_shown('tb3')
        odom = wait_until(self.odom.latest, 30, 'odometry').pose.pose
        x0 = odom.position.x
        self.assertAlmostEqual(x0, -2.0, places=2)
        wait_until(lambda: self.script('return window.courseWeb.tb3ToPixel !== null') and self.text('tb3-pose'),
                   30, 'the page to draw the TurtleBot3')
        # w fifteen times: the teleop's target 0.15 m/s; the robot drives forward; space stops it.
        self.press(*'w' * 15)
        wait_until(lambda: self.odom.latest().pose.pose.position.x > x0 + 0.3, 30, 'w to drive the robot', poll=0.05)
        self.press(' ')
        wait_until(lambda: self.odom.latest().twist.twist.linear.x == 0.0, 10, 'space to stop the robot', poll=0.05)
        odom = self.odom.next_message(timeout=10).pose.pose
        x, y = odom.position.x, odom.position.y
        yaw = 2 * math.atan2(odom.orientation.z, odom.orientation.w)
        scan = self.scan.next_message(timeout=10)
        closest = min(r for r in scan.ranges if scan.range_min <= r <= scan.range_max)
        # Within the page's last digit: the view sends the pose to 0.1 mm and the page prints mm, so
        # the two roundings can put the printed mm up to 0.55 mm from the place (Python rounds once).
        if not poll_until(lambda: printed_near(self.text('tb3-pose'), x, y, 0.00056), 10):
            self.fail('after 10 s the page printed %r, not the pose x %.4f, y %.4f' % (self.text('tb3-pose'), x, y))
        wait_until(lambda: self.text('tb3-closest') == '%.3f m' % closest, 10,
                   'the page to print the closest range %.3f m' % closest)
        pixels = self.canvas('tb3')
        save_pixels(pixels, os.path.join(self.shots, 'course_web-fake_tb3.png'))

        def to_pixel(wx, wy):
            return self.script('return window.courseWeb.tb3ToPixel(%r, %r)' % (wx, wy))
        # The laser's points: each hit the simulator reports is red on the page.
        laser_x, laser_y = x - 0.032 * math.cos(yaw), y - 0.032 * math.sin(yaw)
        hits = [(laser_x + r * math.cos(yaw + scan.angle_min + i * scan.angle_increment),
                 laser_y + r * math.sin(yaw + scan.angle_min + i * scan.angle_increment))
                for i, r in enumerate(scan.ranges) if math.isfinite(r)][::10]
        self.assertGreater(len(hits), 20)
        red = sum(near_colour(pixels, int(round(px)), int(round(py)), LASER_RED, radius=2)
                  for px, py in (to_pixel(hx, hy) for hx, hy in hits))
        self.assertGreaterEqual(red, 0.9 * len(hits), '%d of %d laser hits are red on the page' % (red, len(hits)))
        # The robot: its blue body where odometry says, a pillar grey where the world has it.
        px, py = to_pixel(x - 0.032, y)
        body = pixels[int(py) - 2:int(py) + 3, int(px) - 2:int(px) + 3].reshape(-1, 3).astype(int)
        self.assertTrue(any(p[2] > p[0] + 60 for p in body), body)
        px, py = to_pixel(-1.1, 0.0)
        self.assertTrue(near_colour(pixels, int(px), int(py), (110, 110, 110), radius=0))
        # The path: blue from the start to behind the robot, not beside it.
        for along in (0.05, 0.15):
            px, py = to_pixel(x0 + along, -0.5)
            self.assertTrue(near_colour(pixels, int(round(px)), int(round(py)), (30, 90, 200), radius=1, tolerance=150),
                            pixels[int(py) - 1:int(py) + 2, int(px) - 1:int(px) + 2])
            px, py = to_pixel(x0 + along, -0.4)
            self.assertTrue(near_colour(pixels, int(round(px)), int(round(py)), (250, 250, 250), radius=0, tolerance=30))

    def test_3_several_tabs_and_restarted_simulators(self):
        first = self.browser.current_window_handle
        self.browser.switch_to.new_window('tab')
        self.browser.get('http://localhost:%d/' % self.port)
        wait_until(lambda: self.script('return window.courseWeb.turtlesimFrames') > 0, 30, 'the second tab\'s frames')
        subprocess.run(['rosnode', 'kill', '/turtlesim', '/fake_tb3'], check=True, stdout=subprocess.DEVNULL)
        self.wait_shown('turtlesim', False)
        self.wait_shown('tb3', False)
        # fake_tb3's parameters (world, model) stay on the parameter server: it comes back as it was.
        restarted = [subprocess.Popen(['rosrun', package, node, '__name:=' + name], start_new_session=True,
                                      stdout=subprocess.DEVNULL)
                     for package, node, name in (('turtlesim', 'turtlesim_node', 'turtlesim'),
                                                 ('fake_tb3', 'fake_tb3_node', 'fake_tb3'))]
        for process in restarted:
            self.addCleanup(stop_process_group, process)
        for handle in (self.browser.current_window_handle, first):
            self.browser.switch_to.window(handle)
            self.wait_shown('turtlesim')
            self.wait_shown('tb3')
        pose = self.still_turtle()
        self.wait_page_shows_turtle_at(pose)
        pixels = self.canvas('turtlesim')
        col, row = ts_pixel(5.544445, 5.544445 - 1.0)  # the old trail is gone with the old turtlesim
        self.assertTrue(near_colour(pixels, col, row, TS_BACKGROUND, radius=0), pixels[row, col])
        # The robot is back at its spawn pose, with no path behind it.
        wait_until(lambda: self.text('tb3-pose').startswith('x -2.000 m, y -0.500 m'), 30,
                   'the page to show the restarted robot at its spawn pose')
        self.assertEqual(self.script('return window.courseWeb.tb3TrailLength'), 1)

    def test_4_no_page_no_subscription_and_ctrl_c_leaves_no_port(self):
        pages = self.browser.window_handles
        self.browser.switch_to.new_window('tab')
        for handle in pages:  # closing a tab closes its page's connection
            self.browser.switch_to.window(handle)
            self.browser.close()
        master = rosgraph.Master('/course_web_browser_test')

        def let_go():
            subscribers = dict(master.getSystemState()[1])
            return not any('/course_web' in subscribers.get(topic, ()) for topic in ('/turtlesim/scene', '/odom', '/scan'))
        wait_until(let_go, 15, 'the view to unsubscribe from the simulators with no page left', poll=0.2)
        self.assertEqual(stop_process_group(self.view.process, timeout=10), 0)
        self.assertFalse(port_open(self.port))


if __name__ == '__main__':
    rostest.rosrun('course_web', 'browser', BrowserTest)
