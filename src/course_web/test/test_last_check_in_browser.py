#!/usr/bin/env python3
"""Your last check in the browser: a real `rosrun course_grader check move_turtlebot3` of the
course's own package, into a ROS_HOME of the test's, while the view runs. The check says to open the
view; the page, already open, shows the check within seconds: each criterion with the points and
the sentence of result.json, the pictures (loaded), and each run's player, which plays it."""
import json
import os
import re
import shutil
import subprocess
import tempfile

import rospkg
import rostest

from course_common.waiting import wait_until
from view_in_browser import ViewInBrowser

LAB = 'move_turtlebot3'

PANEL = '''
return [...document.querySelectorAll('#check-criteria li')].map((li) => ({
  id: li.dataset.id, verdict: li.querySelector('.verdict').textContent,
  points: li.querySelector('.points').textContent, title: li.querySelector('.title').textContent,
  reason: li.querySelector('.reason') ? li.querySelector('.reason').textContent : null}));
'''
PICTURES = '''
return [...document.querySelectorAll('#check-pictures img')].map((img) => ({
  name: decodeURIComponent(img.src.split('/').pop()), complete: img.complete, width: img.naturalWidth}));
'''


class LastCheckInBrowserTest(ViewInBrowser):
    @classmethod
    def setUpClass(cls):
        cls.ros_home = tempfile.mkdtemp(prefix='course_web-ros_home-')
        cls.view_environment = {'ROS_HOME': cls.ros_home}   # the view's, and the check's below
        super().setUpClass()
        package = rospkg.RosPack().get_path(LAB)
        checked = subprocess.run(['rosrun', 'course_grader', 'check', LAB, package], stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, universal_newlines=True, timeout=600,
                                 env=dict(os.environ, ROS_HOME=cls.ros_home, COURSE_WEB_PORT=str(cls.port)))
        cls.output = checked.stdout
        assert checked.returncode == 0, cls.output[-3000:]
        checks = os.path.join(cls.ros_home, 'course_check')
        cls.check = os.readlink(os.path.join(checks, 'latest'))
        folder = os.path.join(checks, cls.check)
        cls.summary_folder = folder
        with open(os.path.join(folder, LAB, 'result.json')) as stream:
            cls.result = json.load(stream)

    @classmethod
    def tearDownClass(cls):
        super().tearDownClass()
        shutil.rmtree(cls.ros_home, ignore_errors=True)

    def wait_panel(self):
        wait_until(lambda: self.script('return window.courseLastCheck.check') == self.check, 30,
                   'the page to show the check %s' % self.check)

    def test_a_check_json_not_written_by_the_check_says_to_check_again(self):
        # Runs first (by name), then puts the real check back: the other tests wait for it.
        checks = os.path.join(self.ros_home, 'course_check')
        for number, text in enumerate(('{"lab": "move_turtlebot3", "criteria": ', '{}', 'null')):
            broken = '%s/2000-01-01_00-00-0%d' % (LAB, number)
            os.makedirs(os.path.join(checks, broken))
            with open(os.path.join(checks, broken, 'check.json'), 'w') as stream:
                stream.write(text)
            os.symlink(broken, os.path.join(checks, 'latest.broken'))
            os.replace(os.path.join(checks, 'latest.broken'), os.path.join(checks, 'latest'))
            wait_until(lambda: self.script('return window.courseLastCheck.check') == broken, 30,
                       'the page to take up the check %s' % broken)
            said = self.text('check-error')
            self.assertTrue(said.startswith('This check (%s) cannot be shown: its check.json is not what the '
                                            'check writes (' % broken), said)
            self.assertTrue(said.endswith('). Run `rosrun course_grader check move_turtlebot3` again.'), said)
            self.assertEqual(self.script('return document.querySelectorAll("#check-criteria li").length'), 0)
            self.assertEqual(self.text('check-total'), '')
            if number == 0:
                self.browser.save_screenshot(os.path.join(self.shots, 'course_web-last-check-unreadable.png'))
        os.symlink(self.check, os.path.join(checks, 'latest.back'))
        os.replace(os.path.join(checks, 'latest.back'), os.path.join(checks, 'latest'))
        self.wait_panel()
        self.assertTrue(self.script('return document.getElementById("check-error").hidden'))
        self.assertFalse(self.script('return document.getElementById("check-package-line").hidden'))

    def test_the_check_says_where_it_is_and_to_open_the_view(self):
        student = os.path.join(self.summary_folder, LAB)
        self.assertIn('check: pictures and logs in %s (the last 5 checks of each lab are kept)\n' % student,
                      self.output)
        self.assertIn('check: open http://localhost:%d/ (Your last check): this result, its pictures and each '
                      'run played again\n' % self.port, self.output)

    def test_the_panel_lists_each_criterion_as_result_json_has_it(self):
        self.wait_panel()
        self.assertEqual(self.text('check-lab'), LAB)
        total = re.search(r'^check: (total .*)$', self.output, re.M).group(1)   # as the terminal says it
        self.assertTrue(total.startswith('total %g / %g (' % (self.result['score'], self.result['max_score'])), total)
        self.assertEqual(self.text('check-total'), total)
        shown = self.script(PANEL)
        expected = [{'id': c['id'], 'verdict': 'PASS' if c['passed'] else 'FAIL',
                     'points': '%g / %g' % (c['points'], c['max_points']), 'title': c['title'],
                     'reason': c['reason'] or None} for c in self.result['criteria']]
        self.assertTrue(all(c['visibility'] == 'visible' for c in self.result['criteria']))
        self.assertEqual(len(expected), 7)
        self.assertEqual(shown, expected)
        self.browser.save_screenshot(os.path.join(self.shots, 'course_web-last-check.png'))

    def test_the_pictures_load(self):
        self.wait_panel()
        wait_until(lambda: all(p['complete'] for p in self.script(PICTURES)), 20, 'the pictures to load')
        pictures = self.script(PICTURES)
        self.assertEqual([p['name'] for p in pictures], self.result['pictures'])
        self.assertEqual(self.result['pictures'], ['trajectory.png', 'avoid_obstacle.png'])
        for picture in pictures:
            self.assertGreater(picture['width'], 0, picture)

    def test_each_run_plays_in_the_player(self):
        self.wait_panel()
        links = self.script('return [...document.querySelectorAll("#check-runs a")].map((a) => '
                            '[a.textContent, a.href])')
        self.assertEqual([text for text, _ in links], ['%s, played again' % run for run in
                                                       ('avoid_obstacle', 'laser_data', 'trajectory')])
        try:
            self.browser.get(links[0][1])
            wait_until(lambda: self.script('return window.courseReplayState && '
                                           '(window.courseReplayState.error || window.courseReplayState.duration)'),
                       30, 'the player to load the run')
            state = self.script('return window.courseReplayState')
            self.assertIsNone(state['error'])
            self.assertGreater(state['duration'], 5.0)
            self.assertFalse(self.script('return document.getElementById("tb3").hidden'))   # the robot's world
            self.script('document.getElementById("play").click()')
            wait_until(lambda: self.script('return window.courseReplayState.time') > 1.0, 30, 'the run to play')
        finally:
            self.browser.get('http://localhost:%d/' % self.port)


if __name__ == '__main__':
    rostest.rosrun('course_web', 'last_check_in_browser', LastCheckInBrowserTest)
