"""What the browser tests share: the view started on a port of its own and headless chromium on its page
(for a unittest.TestCase's class), and how to read what the page shows."""
import os
import unittest

import numpy as np
import rospy
from selenium.webdriver.common.by import By

from course_testing.browser import element_pixels, start_browser
from course_testing.pictures import picture_folder
from course_testing.processes import LoggedLaunch
from course_common.waiting import wait_until
from course_web.ros_view import served_port

TS_PX_PER_METER = 45
TS_BACKGROUND = (69, 86, 255)


def ts_pixel(x, y):
    """turtlesim's canvas pixel (column, row) of a point in metres."""
    return int(round(x * TS_PX_PER_METER)), int(round(499 - y * TS_PX_PER_METER))


def near_colour(pixels, col, row, colour, radius=2, tolerance=40):
    patch = pixels[max(0, row - radius):row + radius + 1, max(0, col - radius):col + radius + 1]
    return bool((np.abs(patch.astype(int) - colour).sum(axis=2) <= tolerance).any())


class ViewInBrowser(unittest.TestCase):
    """The view (node /course_web) and one browser tab on it; screenshots go to the directory in
    $COURSE_WEB_SCREENSHOTS, else to the test's picture folder (logged). view_environment: what
    the view's environment has besides this process's."""
    view_environment = {}

    @classmethod
    def setUpClass(cls):
        rospy.init_node('course_web_browser_test')
        cls.shots = (os.environ.get('COURSE_WEB_SCREENSHOTS') or
                     picture_folder('course_web', rospy.get_name().lstrip('/')))
        os.makedirs(cls.shots, exist_ok=True)
        rospy.loginfo('course_web test: screenshots in %s', cls.shots)
        # On port 0, at the port it says: a port found free here could be taken before the view
        # listens, and whatever listened there would answer for it.
        cls.view = LoggedLaunch(['rosrun', 'course_web', 'view', '__name:=course_web', '_port:=0'],
                                os.path.join(cls.shots, 'view.log'), dict(os.environ, **cls.view_environment))
        cls.port = wait_until(lambda: served_port(cls.view.output()), 60,
                              'the view to say where it serves (%s)' % cls.view.log_path, poll=0.2)
        cls.browser = start_browser()
        cls.browser.get('http://localhost:%d/' % cls.port)

    @classmethod
    def tearDownClass(cls):
        cls.browser.quit()
        cls.view.stop()

    def script(self, text):
        return self.browser.execute_script(text)

    def canvas(self, name):
        return element_pixels(self.browser.find_element(By.ID, name + '-canvas'))

    def text(self, element_id):
        return self.script('return document.getElementById(%r).textContent' % element_id)

    def press(self, *keys):
        body = self.browser.find_element(By.TAG_NAME, 'body')
        for key in keys:
            body.send_keys(key)

    def wait_shown(self, part, shown=True):
        """Wait until the page shows (or hides) its part: 'turtlesim' or 'tb3'."""
        wait_until(lambda: self.script('return document.getElementById(%r).hidden' % part) != shown, 30,
                   'the page to %s %s' % ('show' if shown else 'hide', part))

    def wait_page_shows_turtle_at(self, pose):
        def shown():
            drawn = self.script('const d = window.courseWeb.drawn.filter(e => e[0] === "turtle1"); '
                                'return d.length ? d[d.length - 1][1] : null')
            return drawn is not None and abs(drawn - pose.x) < 1e-4
        wait_until(shown, 20, 'the page to draw turtle1 at x = %.4f' % pose.x, poll=0.05)
