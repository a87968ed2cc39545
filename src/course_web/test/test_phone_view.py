#!/usr/bin/env python3
"""The page on phones and tablets (chromium's mobile emulation: the screen's size, touch, a phone's
user agent): each world as wide as the screen with no sideways scrolling, readable text, and the
teleops' keys as buttons big enough for a thumb, which a touch presses as the key: a tap is one key
press, holding repeats it. On a desktop the buttons are not shown."""
import base64
import os

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from course_common.topic_recorder import TopicRecorder
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute
from turtlesim.world import TICK_SECONDS
from view_in_browser import ViewInBrowser

PHONE_AGENT = ('Mozilla/5.0 (Linux; Android 14; Pixel 8) AppleWebKit/537.36 (KHTML, like Gecko) '
               'Chrome/120.0.0.0 Mobile Safari/537.36')
# CSS pixels: phones in portrait and on their side, a tablet.
SCREENS = ((390, 844), (844, 390), (360, 640), (640, 360), (768, 1024))
MIN_TARGET = 44        # CSS px: the smallest touch target the platforms' guidelines allow
MIN_TEXT = 12          # CSS px
BODY_MARGIN = 16       # CSS px: the page's margin (1em)
TB3_KEY_STEP = 0.01    # m/s: turtlebot3_teleop_key's w

LAYOUT = '''
const box = (e) => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; };
return {innerWidth: innerWidth, innerHeight: innerHeight, scrollWidth: document.documentElement.scrollWidth,
        canvases: [...document.querySelectorAll('canvas')].map(box),
        pads: [...document.querySelectorAll('.pad')].map((p) => getComputedStyle(p).display),
        buttons: [...document.querySelectorAll('.pad button')].map(box),
        smallestText: Math.min(...[...document.querySelectorAll('p, td, th, h2')].map(
            (e) => parseFloat(getComputedStyle(e).fontSize)))};
'''


class PhoneViewTest(ViewInBrowser):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.pose = TopicRecorder('/turtle1/pose', Pose)
        cls.turtle_commands = TopicRecorder('/turtle1/cmd_vel', Twist)
        cls.tb3_commands = TopicRecorder('/cmd_vel', Twist)
        cls.odom = TopicRecorder('/odom', Odometry)

    def open_on(self, width, height):
        """The page reloaded on a touch screen of width x height CSS px."""
        cdp = self.browser.execute_cdp_cmd
        cdp('Emulation.setDeviceMetricsOverride', {'width': width, 'height': height, 'mobile': True,
                                                   'deviceScaleFactor': 3 if min(width, height) < 600 else 2})
        cdp('Emulation.setTouchEmulationEnabled', {'enabled': True, 'maxTouchPoints': 5})
        cdp('Emulation.setUserAgentOverride', {'userAgent': PHONE_AGENT})
        self.browser.get('http://localhost:%d/' % self.port)
        self.wait_shown('turtlesim')
        self.wait_shown('tb3')

    def button_centre(self, pad, name):
        """Where a touch lands on a pad's button (scrolled into view), in CSS px of the screen."""
        x, y, hit = self.script(
            'const b = document.querySelector("#%s-pad .%s"); b.scrollIntoView({block: "center"});'
            'const r = b.getBoundingClientRect(), x = r.left + r.width / 2, y = r.top + r.height / 2;'
            'return [x, y, document.elementFromPoint(x, y) === b];' % (pad, name))
        self.assertTrue(hit, 'the %s button of %s is under something else' % (name, pad))
        return x, y

    def touch(self, x, y):
        self.browser.execute_cdp_cmd('Input.dispatchTouchEvent', {'type': 'touchStart', 'touchPoints': [{'x': x, 'y': y}]})

    def lift(self):
        self.browser.execute_cdp_cmd('Input.dispatchTouchEvent', {'type': 'touchEnd', 'touchPoints': []})

    def tap(self, pad, name):
        self.touch(*self.button_centre(pad, name))
        self.lift()

    def still_turtle(self):
        def still():
            pose = self.pose.latest()
            return pose if pose is not None and pose.linear_velocity == 0 and pose.angular_velocity == 0 else None
        return wait_until(still, 20, 'turtle1 to stand still', poll=0.05)

    def settled_tb3_command(self):
        """The TurtleBot3 command once the view's ramp has reached the keys' target (three equal in a row)."""
        def settled():
            last = [m.linear.x for m in self.tb3_commands.messages(max(0, self.tb3_commands.count() - 3))]
            return len(last) == 3 and last[0] == last[1] == last[2] and [last[0]]
        return wait_until(settled, 20, 'the TurtleBot3 command to settle', poll=0.05)[0]

    def test_1_a_desktop_shows_no_buttons(self):
        self.wait_shown('turtlesim')
        self.wait_shown('tb3')
        layout = self.script(LAYOUT)
        self.assertEqual(layout['pads'], ['none', 'none'])
        # The worlds as large as before: the simulators' 500 px and a 1 px border.
        self.assertEqual([c[2:] for c in layout['canvases']], [[502, 502], [502, 502]])

    def test_2_phones_and_a_tablet_fit_the_screen_and_show_big_buttons(self):
        for width, height in SCREENS:
            screen = 'on a %dx%d screen' % (width, height)
            self.open_on(width, height)
            layout = self.script(LAYOUT)
            # The viewport meta tag: the page is laid out for the screen's width, not zoomed out.
            self.assertEqual(layout['innerWidth'], width, screen)
            self.assertLessEqual(layout['scrollWidth'], width, 'the page scrolls sideways ' + screen)
            self.assertGreaterEqual(layout['smallestText'], MIN_TEXT, screen)
            for left, top, w, h in layout['canvases']:
                self.assertTrue(0 <= left and left + w <= width, 'a world sticks out ' + screen)
                self.assertAlmostEqual(w, h, delta=0.5, msg=screen)
                if width < height:  # upright: as wide as the screen (or the simulator's 500 px)
                    self.assertGreaterEqual(w, min(502, width - 2 * BODY_MARGIN) - 1, screen)
                else:  # on its side: the whole world fits the screen's height
                    self.assertLessEqual(h, height - 2 * BODY_MARGIN, screen)
            self.assertEqual(layout['pads'], ['grid', 'grid'], screen)
            self.assertEqual(len(layout['buttons']), 9, screen)
            for left, top, w, h in layout['buttons']:
                self.assertGreaterEqual(min(w, h), MIN_TARGET, screen)
                self.assertTrue(0 <= left and left + w <= width, 'a button sticks out ' + screen)

    def test_3_a_tap_on_forward_moves_turtle1_as_the_up_arrow(self):
        self.open_on(390, 844)
        wait_until(lambda: self.turtle_commands.subscriber.get_num_connections() > 0, 30,
                   'the test to listen to the view on turtle1/cmd_vel', poll=0.2)
        start = self.still_turtle()
        heard = self.turtle_commands.count()
        self.tap('turtlesim', 'forward')  # turtle_teleop_key's up arrow: 2 m/s for 1 s, along +x
        wait_until(lambda: self.pose.latest().x > start.x + 0.5, 20, 'the forward button to move turtle1', poll=0.02)
        end = self.still_turtle()
        self.assertAlmostEqual(end.x - start.x, 2.0 * 63 * TICK_SECONDS, delta=0.1)
        self.assertAlmostEqual(end.y, start.y, places=3)
        self.assertEqual([(c.linear.x, c.angular.z) for c in self.turtle_commands.messages(heard)], [(2.0, 0.0)],
                         'a tap is one press of the up arrow')
        self.wait_page_shows_turtle_at(end)
        self.script('window.scrollTo(0, 0)')
        shot = self.browser.execute_cdp_cmd('Page.captureScreenshot', {'format': 'png'})
        with open(os.path.join(self.shots, 'course_web-phone.png'), 'wb') as png:
            png.write(base64.b64decode(shot['data']))

    def test_4_holding_forward_repeats_it_until_the_finger_lifts(self):
        self.open_on(390, 844)
        self.still_turtle()
        rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(1.0, 5.5, 0.0)
        wait_until(lambda: abs(self.pose.latest().x - 1.0) < 1e-4, 20, 'the teleport', poll=0.02)
        start = self.still_turtle()
        heard = self.turtle_commands.count()
        self.touch(*self.button_centre('turtlesim', 'forward'))
        try:  # one up arrow drives it 2 m (2 m/s for 1 s): farther, the button has repeated
            wait_until(lambda: self.pose.latest().x > start.x + 2.5, 20, 'holding the button to drive turtle1 on',
                       poll=0.02)
        finally:
            self.lift()
        # It stops (a button repeating on would drive it into the wall, and on against it), and all it
        # sent were up arrows.
        end = self.still_turtle()
        self.assertLess(end.x, 9.0)
        commands = self.turtle_commands.messages(heard)
        self.assertGreaterEqual(len(commands), 3)
        self.assertEqual({(c.linear.x, c.angular.z) for c in commands}, {(2.0, 0.0)})

    def test_5_the_turtlebot3_buttons_step_as_w_and_stop_as_s(self):
        self.open_on(390, 844)
        self.tap('tb3', 'forward')  # one press of w: the target speed goes up one step
        self.assertAlmostEqual(self.settled_tb3_command(), TB3_KEY_STEP, places=6)
        self.odom.wait_for(lambda o: o.twist.twist.linear.x > TB3_KEY_STEP / 2, 20, 'the robot to drive')
        self.tap('tb3', 'stop')
        self.odom.wait_for(lambda o: o.twist.twist.linear.x == 0.0, 20, 'the stop button to stop the robot')
        self.assertEqual(self.tb3_commands.latest().linear.x, 0.0)

if __name__ == '__main__':
    rostest.rosrun('course_web', 'phone_view', PhoneViewTest)
