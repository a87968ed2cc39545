#!/usr/bin/env python3
"""The page in a real browser (headless chromium), beside turtlesim and fake_tb3 in turtlebot3_world:
what it draws is where the simulators say, its keys drive them, it follows a restarted turtlesim,
and Ctrl-C leaves no port behind. Screenshots: the directory in $COURSE_WEB_SCREENSHOTS, else a
temporary one (logged)."""
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np
import rospy
import rostest
from nav_msgs.msg import Odometry
from PIL import Image
from sensor_msgs.msg import LaserScan
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from std_srvs.srv import Trigger

from course_testing.browser import element_pixels, save_pixels, start_browser
from course_testing.processes import free_port, port_open, stop_process_group
from course_testing.recording import TopicRecorder
from course_testing.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import SetPen, TeleportAbsolute

TS_PX_PER_METER = 45
RED = np.array([255, 0, 0])
LASER_RED = np.array([230, 20, 20])
PEN_WIDTH = 4


def ts_pixel(x, y):
    """turtlesim's canvas pixel (column, row) of a point in metres."""
    return int(round(x * TS_PX_PER_METER)), int(round(499 - y * TS_PX_PER_METER))


def near_colour(pixels, col, row, colour, radius=2, tolerance=40):
    patch = pixels[max(0, row - radius):row + radius + 1, max(0, col - radius):col + radius + 1]
    return bool((np.abs(patch.astype(int) - colour).sum(axis=2) <= tolerance).any())


class BrowserTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('course_web_browser_test')
        cls.shots = os.environ.get('COURSE_WEB_SCREENSHOTS') or tempfile.mkdtemp(prefix='course_web-')
        os.makedirs(cls.shots, exist_ok=True)
        rospy.loginfo('course_web test: screenshots in %s', cls.shots)
        cls.port = free_port()
        cls.view = subprocess.Popen(['rosrun', 'course_web', 'view', '__name:=course_web',
                                     '_port:=%d' % cls.port], start_new_session=True)
        wait_until(lambda: port_open(cls.port), 60, 'the view to listen on port %d' % cls.port, poll=0.2)
        cls.browser = start_browser()
        cls.browser.get('http://localhost:%d/' % cls.port)
        cls.pose = TopicRecorder('/turtle1/pose', Pose)
        cls.odom = TopicRecorder('/odom', Odometry)
        cls.scan = TopicRecorder('/scan', LaserScan)

    @classmethod
    def tearDownClass(cls):
        cls.browser.quit()
        stop_process_group(cls.view)

    def script(self, text):
        return self.browser.execute_script(text)

    def canvas(self, name):
        return element_pixels(self.browser.find_element(By.ID, name + '-canvas'))

    def press(self, *keys):
        body = self.browser.find_element(By.TAG_NAME, 'body')
        for key in keys:
            body.send_keys(key)

    def still_turtle(self):
        def still():
            pose = self.pose.latest()
            return pose if pose is not None and pose.linear_velocity == 0 and pose.angular_velocity == 0 else None
        return wait_until(still, 20, 'turtle1 to stand still', poll=0.05)

    def wait_page_shows_turtle_at(self, pose):
        def shown():
            drawn = self.script('const d = window.courseWeb.drawn.filter(e => e[0] === "turtle1"); '
                                'return d.length ? d[d.length - 1][1] : null')
            return drawn is not None and abs(drawn - pose.x) < 1e-4
        wait_until(shown, 20, 'the page to draw turtle1 at x = %.4f' % pose.x, poll=0.05)

    def test_1_turtlesim_turtle_trail_and_keys(self):
        wait_until(lambda: self.script('return !document.getElementById("turtlesim").hidden'), 30,
                   'the page to show turtlesim')
        rospy.wait_for_service('/turtle1/set_pen', 10)
        rospy.ServiceProxy('/turtle1/set_pen', SetPen)(255, 0, 0, PEN_WIDTH, 0)
        rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(2.0, 3.0, 0.0)
        wait_until(lambda: abs(self.pose.latest().x - 2.0) < 1e-4, 10, 'the teleport', poll=0.02)
        start = self.still_turtle()
        self.press(Keys.ARROW_UP)  # turtle_teleop_key: 2 m/s for 1 s, along +x
        wait_until(lambda: self.pose.latest().x > start.x + 0.5, 20, 'the arrow key to move turtle1', poll=0.02)
        end = self.still_turtle()
        self.assertAlmostEqual(end.x - start.x, 2.0 * 63 * 0.016, delta=0.1)
        self.assertAlmostEqual(end.y, start.y, places=3)
        self.wait_page_shows_turtle_at(end)
        pixels = self.canvas('turtlesim')
        save_pixels(pixels, os.path.join(self.shots, 'course_web-turtlesim.png'))
        self.assertEqual(pixels.shape, (500, 500, 3))
        # The trail: red from the start to behind the turtle, background beside it.
        for fraction in (0.3, 0.5, 0.7):
            col, row = ts_pixel(start.x + fraction * (end.x - start.x), start.y)
            self.assertTrue(near_colour(pixels, col, row, RED, radius=0), (col, row, pixels[row, col]))
            self.assertTrue(near_colour(pixels, col, row + 6, (69, 86, 255), radius=0), pixels[row + 6, col])
        # The teleport's line, from the centre to (2, 3), is there too.
        col, row = ts_pixel((5.544445 + 2.0) / 2, (5.544445 + 3.0) / 2)
        self.assertTrue(near_colour(pixels, col, row, RED, radius=1), pixels[row - 1:row + 2, col - 1:col + 2])
        # The turtle: its shell (neither background nor pen) where the simulator says it is.
        col, row = ts_pixel(end.x, end.y)
        centre = pixels[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3).astype(int)
        self.assertFalse(any((abs(p - (69, 86, 255)).sum() < 30 or abs(p - RED).sum() < 30) for p in centre), centre)
        # Everywhere away from the turtle (and its name below it), the page has turtlesim's own pixels.
        saved = rospy.ServiceProxy('/turtlesim/save_canvas', Trigger)()
        self.assertTrue(saved.success, saved.message)
        original = np.array(Image.open(saved.message).convert('RGB'))
        mask = np.ones((500, 500), bool)
        mask[max(0, row - 25):row + 45, max(0, col - 40):col + 40] = False
        same = (np.abs(original.astype(int) - pixels.astype(int)).sum(axis=2) <= 3)[mask].mean()
        self.assertGreater(same, 0.999, 'page and turtlesim differ in %.3f %% of the pixels' % (100 * (1 - same)))
        # Left arrow: turns turtle1 by +2 rad/s for 1 s.
        self.press(Keys.ARROW_LEFT)
        wait_until(lambda: self.pose.latest().theta > 0.5, 20, 'the left arrow to turn turtle1', poll=0.02)

    def test_2_fake_tb3_robot_scan_and_keys(self):
        wait_until(lambda: self.script('return !document.getElementById("tb3").hidden'), 30,
                   'the page to show the TurtleBot3')
        scan = wait_until(self.scan.latest, 30, 'a scan')
        odom = wait_until(self.odom.latest, 30, 'odometry').pose.pose
        x, y = odom.position.x, odom.position.y
        yaw = 2 * math.atan2(odom.orientation.z, odom.orientation.w)
        self.assertAlmostEqual(x, -2.0, places=2)
        wait_until(lambda: self.script('return window.courseWeb.tb3ToPixel !== null && '
                                       'document.getElementById("tb3-closest").textContent !== ""'), 30,
                   'the page to draw the TurtleBot3')
        scan = self.scan.next_message(timeout=10)
        wait_until(lambda: self.script('return window.courseWeb.tb3Frames') > 0, 10, 'frames')
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
        self.assertIn('x -2.000 m, y -0.500 m', self.script('return document.getElementById("tb3-pose").textContent'))
        # w three times: the teleop's target 0.03 m/s; the robot drives forward; space stops it.
        self.press('w', 'w', 'w')
        wait_until(lambda: self.odom.latest().pose.pose.position.x > x + 0.01, 30, 'w to drive the robot', poll=0.05)
        self.press(' ')
        wait_until(lambda: self.odom.latest().twist.twist.linear.x == 0.0, 10, 'space to stop the robot', poll=0.05)

    def test_3_several_tabs_and_a_restarted_turtlesim(self):
        first = self.browser.current_window_handle
        self.browser.switch_to.new_window('tab')
        self.browser.get('http://localhost:%d/' % self.port)
        wait_until(lambda: self.script('return window.courseWeb.turtlesimFrames') > 0, 30, 'the second tab\'s frames')
        subprocess.run(['rosnode', 'kill', '/turtlesim'], check=True, stdout=subprocess.DEVNULL)
        wait_until(lambda: self.script('return document.getElementById("turtlesim").hidden'), 30,
                   'the page to notice turtlesim is gone')
        restarted = subprocess.Popen(['rosrun', 'turtlesim', 'turtlesim_node'], start_new_session=True,
                                     stdout=subprocess.DEVNULL)
        self.addCleanup(stop_process_group, restarted)
        for handle in (self.browser.current_window_handle, first):
            self.browser.switch_to.window(handle)
            wait_until(lambda: self.script('return !document.getElementById("turtlesim").hidden'), 30,
                       'the page to show the restarted turtlesim')
        pose = self.still_turtle()
        self.wait_page_shows_turtle_at(pose)
        pixels = self.canvas('turtlesim')
        col, row = ts_pixel(2.0 + 0.5, 3.0)  # the old trail is gone with the old turtlesim
        self.assertTrue(near_colour(pixels, col, row, (69, 86, 255), radius=0), pixels[row, col])

    def test_4_ctrl_c_leaves_no_port(self):
        self.assertEqual(stop_process_group(self.view, timeout=10), 0)
        self.assertFalse(port_open(self.port))


if __name__ == '__main__':
    rostest.rosrun('course_web', 'browser', BrowserTest)
