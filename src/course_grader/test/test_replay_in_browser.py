#!/usr/bin/env python3
"""report.html's players in a real browser (headless chromium), opened from file:// as a teacher
opens the folder: a report made from runs kept as the grader keeps them (replay_bags), each run in
its frame. Play at a speed moves the robot (its laser points) and draws the turtle's circle where
the bags put them, the slider follows, the judged moments show as the run passes them, seeking back
redraws the run's start, a bag that cannot be read is a sentence, and on a phone-sized screen the
player fits with thumb-sized controls, and the class table scrolls in its own box. Screenshots go
to $REPLAY_SCREENSHOTS, else a temporary folder (logged)."""
import os
import shutil
import tempfile
import unittest

import numpy as np
import rostest
from selenium.webdriver.common.by import By

from course_checks.verdict import Verdict
from course_common.waiting import wait_until
from course_grader import reports, results, rubric
from course_testing.browser import element_pixels, save_pixels, start_browser
from course_testing.pictures import picture_folder
import replay_bags

LASER_RED = np.array([230, 20, 20])
PEN_RED = np.array([255, 0, 0])
TS_PX_PER_METER = 45


def near(pixels, colour, tolerance=60):
    """(rows, cols) of the pixels within tolerance of colour (sum of the channels' differences)."""
    return np.nonzero(np.abs(pixels.astype(int) - colour).sum(axis=2) <= tolerance)


class ReplayInBrowser(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp(prefix='replay-report-')
        cls.shots = os.environ.get('REPLAY_SCREENSHOTS') or picture_folder('course_grader', 'replay_in_browser')
        os.makedirs(cls.shots, exist_ok=True)
        print('replay test: screenshots in %s' % cls.shots)
        replay_bags.write_class(cls.out)
        os.makedirs(os.path.join(cls.out, 'bob'))
        with open(os.path.join(cls.out, 'bob', 'avoid_obstacle.bag'), 'wb') as stream:
            stream.write(b'#ROSBAG V2.0\ncut short')
        lab = rubric.load('move_turtlebot3')
        graded = [results.score(lab, {c.id: Verdict(True, 'ok') for c in lab.criteria}, name, seconds=3)
                  for name in ('alice', 'bob')]
        reports.write_all(graded, lab, cls.out, seconds=6)
        cls.browser = start_browser(900, 1000)
        cls.browser.get('file://%s/report.html' % cls.out)

    @classmethod
    def tearDownClass(cls):
        cls.browser.quit()
        shutil.rmtree(cls.out, ignore_errors=True)

    def script(self, text, *args):
        return self.browser.execute_script(text, *args)

    def open_run(self, run):
        """Into the frame of alice's run, once its data is drawn: its state (courseReplayState)."""
        self.browser.switch_to.default_content()
        frame = self.browser.find_element(By.CSS_SELECTOR, 'iframe[src$="#alice/%s"]' % run)
        self.script('arguments[0].scrollIntoView()', frame)
        self.browser.switch_to.frame(frame)
        return wait_until(lambda: self.state() if self.state() and self.state()['index'] >= 0 else None, 30,
                          'the player of %s to draw its first frame' % run, poll=0.05)

    def state(self):
        return self.script('return window.courseReplayState || null')

    def canvas(self, name):
        return element_pixels(self.browser.find_element(By.ID, name + '-canvas'))

    def play(self, speed):
        self.browser.find_element(By.CSS_SELECTOR, '.speeds button[data-speed="%s"]' % speed).click()
        self.browser.find_element(By.ID, 'play').click()

    def pause_at(self, seconds):
        """Pause (the play button) once the run has played `seconds`, from inside the page: a click
        from here could come after the run ended, and play it again."""
        self.browser.set_script_timeout(30)
        played = self.browser.execute_async_script('''
            const [seconds, done] = arguments;
            const timer = setInterval(() => {
                if (window.courseReplayState.time >= seconds) {
                    clearInterval(timer);
                    document.getElementById('play').click();
                    done(window.courseReplayState.time);
                }
            }, 5);''', seconds)
        self.assertLess(played, self.state()['duration'])

    def page_shot(self, name):
        self.browser.switch_to.default_content()
        self.browser.save_screenshot(os.path.join(self.shots, name))

    def laser_centre(self):
        """Where the canvas shows the laser: the centre of its red points (a ring 1 m around it),
        in canvas pixels."""
        pixels = self.canvas('tb3')
        rows, cols = near(pixels, LASER_RED)
        self.assertGreater(len(rows), 200, 'no laser points drawn')
        scale = 500.0 / pixels.shape[1]   # the canvas' pixels per pixel on the screen
        return np.array([cols.mean() * scale, rows.mean() * scale])

    def expected_pixel(self, x, y):
        return np.array(self.script('return window.courseWeb.tb3ToPixel(arguments[0], arguments[1])', x, y))

    def test_1_the_robot_drives_as_its_bag_says_and_the_stop_is_marked(self):
        state = self.open_run('avoid_obstacle')
        self.assertAlmostEqual(state['duration'], 10.0, delta=0.05)
        self.assertFalse(state['playing'])
        self.assertIn('x -2.000 m, y -0.500 m', self.script('return document.getElementById("tb3-pose").textContent'))
        spawn = replay_bags.TB3_SPAWN
        laser = self.laser_centre()
        np.testing.assert_allclose(laser, self.expected_pixel(spawn[0] - 0.032, spawn[1]), atol=3)
        self.assertEqual(self.script('return document.getElementById("mark-now").textContent'), '')
        ticks = self.script('return Array.from(document.querySelectorAll("#ticks span")).map(s => [s.textContent, s.style.left])')
        self.assertEqual(ticks, [['1', '60%']])   # the stop, 6 s into 10

        self.play(2)
        self.pause_at(7.0)
        state = self.state()
        self.assertFalse(state['playing'])
        self.assertGreater(float(self.script('return document.getElementById("slider").value')), 6.9)
        end = spawn[0] + replay_bags.TB3_SPEED * replay_bags.TB3_STOP
        self.assertIn('x %.3f m' % end, self.script('return document.getElementById("tb3-pose").textContent'))
        moved = self.laser_centre()
        np.testing.assert_allclose(moved, self.expected_pixel(end - 0.032, spawn[1]), atol=3)
        self.assertGreater(moved[0] - laser[0], 50)
        self.assertEqual(self.script('return document.getElementById("mark-now").textContent'),
                         '6.0 s: stopped after 1.20 m: front beam 0.42 m (avoid_stops)')
        self.assertEqual(self.script('return document.querySelector("#ticks span.now").textContent'), '1')
        self.page_shot('replay-tb3.png')

    def test_2_the_turtle_draws_its_circle_and_seeking_back_redraws_the_start(self):
        self.open_run('circle')
        before = self.canvas('turtlesim')
        self.assertEqual(len(near(before, PEN_RED)[0]), 0)
        self.play(4)
        wait_until(lambda: not self.state()['playing'], 20, 'the run to play to its end at 4x', poll=0.05)
        state = self.state()
        self.assertEqual(state['time'], state['duration'])
        pixels = self.canvas('turtlesim')
        scale = pixels.shape[1] / 500.0
        for x, y in ((5.5, 7.5), (7.5, 5.5), (3.5, 5.5)):   # the top, right and left of the circle
            col, row = x * TS_PX_PER_METER * scale, (499 - y * TS_PX_PER_METER) * scale
            patch = pixels[int(row) - 3:int(row) + 4, int(col) - 3:int(col) + 4]
            self.assertGreater(len(near(patch, PEN_RED)[0]), 0, 'no red pen at (%g, %g)' % (x, y))
        self.assertIn('a full turn driven: the circle closes (circle)',
                      self.script('return document.getElementById("mark-now").textContent'))
        save_pixels(pixels, os.path.join(self.shots, 'replay-turtlesim-canvas.png'))
        # Back to the start with the slider: the run's first picture, no pen line yet, no mark.
        self.script('const s = document.getElementById("slider"); s.value = "0"; '
                    's.dispatchEvent(new Event("input"))')
        wait_until(lambda: self.state()['index'] == 0, 10, 'the player to show the first frame again', poll=0.05)
        wait_until(lambda: len(near(self.canvas('turtlesim'), PEN_RED)[0]) == 0, 10,
                   'the canvas to show the run\'s start (no pen line)', poll=0.1)
        self.assertEqual(self.script('return document.getElementById("mark-now").textContent'), '')
        self.page_shot('replay-turtlesim.png')

    def test_3_a_bag_that_cannot_be_read_is_a_sentence_and_the_frames_fit_their_players(self):
        self.browser.switch_to.default_content()
        errors = [e.text for e in self.browser.find_elements(By.CSS_SELECTOR, '.replay-error')]
        self.assertEqual(len(errors), 1)
        self.assertTrue(errors[0].startswith('The run avoid_obstacle cannot be replayed: its bag cannot be read ('),
                        errors[0])
        self.assertIn('bob: 14 / 14', self.browser.find_element(By.ID, 'bob').text)
        # Each frame as tall as its player says (report.html listens to the frames' messages).
        frame = self.browser.find_element(By.CSS_SELECTOR, 'iframe[src$="#alice/avoid_obstacle"]')
        outer = frame.size['height']
        self.browser.switch_to.frame(frame)
        inner = self.script('return document.documentElement.scrollHeight')
        self.assertLessEqual(abs(outer - inner), 4, 'frame %d px high, its player %d px' % (outer, inner))

    def test_4_on_a_phone_sized_screen_the_player_fits_with_thumb_sized_controls(self):
        self.browser.set_window_size(390, 844)
        try:
            # The report itself: the class table scrolls in its own box, the page never sideways,
            # and each student's score is in view beside the name.
            self.browser.switch_to.default_content()
            self.script('window.scrollTo(0, 0)')
            width = self.script('return document.documentElement.clientWidth')
            self.assertLessEqual(width, 390)
            self.assertLessEqual(self.script('return document.documentElement.scrollWidth'), width)
            table = self.browser.find_element(By.CSS_SELECTOR, 'table.summary')
            self.assertGreater(self.script('return arguments[0].parentNode.scrollWidth', table),
                               self.script('return arguments[0].parentNode.clientWidth', table))
            score = self.browser.find_element(By.XPATH, '//table[@class="summary"]//tr[td/a="alice"]/td[3]')
            self.assertEqual(score.text, '14 / 14')
            self.assertLessEqual(self.script('return arguments[0].getBoundingClientRect().right', score), width)
            self.page_shot('report-phone.png')
            self.open_run('avoid_obstacle')
            self.assertLessEqual(self.script('return document.documentElement.scrollWidth'),
                                 self.script('return document.documentElement.clientWidth'))
            canvas = self.browser.find_element(By.ID, 'tb3-canvas')
            self.assertLessEqual(canvas.size['width'], 390)
            for button in self.browser.find_elements(By.CSS_SELECTOR, '#player button'):
                self.assertGreaterEqual(min(button.size['width'], button.size['height']), 36, button.text)
            self.browser.find_element(By.CSS_SELECTOR, '#marks button').click()   # a tap on the stop: there
            wait_until(lambda: abs(self.state()['time'] - 6.0) < 1e-6 and self.state()['index'] > 0, 10,
                       'the player to go to the marked stop', poll=0.05)
            self.page_shot('replay-phone.png')
        finally:
            self.browser.set_window_size(900, 1000)


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'replay_in_browser', ReplayInBrowser)
