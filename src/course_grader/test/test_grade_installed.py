#!/usr/bin/env python3
"""The grader as a teacher installs and feeds it: from an install space (no source tree, no devel
space) on the folder Moodle's "download all" gives, graded twice into one --out. A step of ./test.sh
of its own, beside grade_examples.test (which grades the model from the devel space)."""
import os
import shutil
import subprocess
import tempfile
import unittest

import rostest

from example_class import ROOT, make_class, read_results

# What grading the move_turtlebot3 lab needs from the workspace: the grader, its checks, the
# simulators and the packages whose environment hooks every course shell has (not the test helpers).
INSTALLED = ['course_checks', 'course_common', 'course_environment', 'course_grader', 'course_web', 'fake_tb3',
             'ros_loopback', 'turtlebot3_teleop', 'turtlesim']


class GradeAsInstalledTest(unittest.TestCase):

    @staticmethod
    def bare_shell(home):
        """A teacher's shell before any workspace is sourced: built in it, the install space's
        setup.bash chains to Debian's ROS only, not to this workspace's devel space. Its ROS_HOME is
        in HOME, as a teacher's own is (rospack takes the passwd entry's home, not HOME)."""
        return {'HOME': home, 'PATH': '/usr/bin:/bin', 'ROS_HOME': os.path.join(home, '.ros')}

    def test_the_installed_grader_grades_a_moodle_download_then_regrades_it(self):
        """The name as Moodle wrote it and its id in the reports, then what changed since the first
        run; every run in a shell with the install space only."""
        with tempfile.TemporaryDirectory() as folder:
            build = subprocess.run(['catkin_make', '--source', os.path.join(ROOT, 'src'), '--build',
                                    os.path.join(folder, 'build'), '-DCATKIN_DEVEL_PREFIX=%s/devel' % folder,
                                    '-DCMAKE_INSTALL_PREFIX=%s/install' % folder, '-DPYTHON_EXECUTABLE=/usr/bin/python3',
                                    '-DCATKIN_WHITELIST_PACKAGES=%s' % ';'.join(INSTALLED), 'install'],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                   stdin=subprocess.DEVNULL, env=self.bare_shell(folder))
            self.assertEqual(build.returncode, 0, build.stdout[-3000:])
            students = make_class('move_turtlebot3', os.path.join(folder, 'class'))
            moodle = os.path.join(folder, 'moodle', 'José Núñez_4711_assignsubmission_file_')
            os.makedirs(moodle)
            out = os.path.join(folder, 'grades')

            def grade(package):
                shutil.make_archive(os.path.join(moodle, 'catkin_ws'), 'zip', package)
                # No source tree, no devel space on any path.
                run = subprocess.run(['bash', '-c', 'source "$1/install/setup.bash" && cd / && rosrun course_grader '
                                      'grade --help | grep "rubrics in" && rosrun course_grader grade move_turtlebot3 '
                                      '"$2" --no-container --out "$3"', 'grade', folder, moodle, out],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                     stdin=subprocess.DEVNULL, env=self.bare_shell(folder))
                print(run.stdout)
                self.assertEqual(run.returncode, 0, run.stdout)
                self.assertIn('(rubrics in %s/install/share/course_grader/rubrics)' % folder, run.stdout)
                os.remove(os.path.join(moodle, 'catkin_ws.zip'))
                return run.stdout

            first = grade(students['into_the_wall'])
            self.assertIn('grade: [1/1] José Núñez (4711): 9 / 14', first)
            rows, details = read_results(out)
            self.assertEqual((rows['José Núñez']['id'], rows['José Núñez']['score']), ('4711', '9'), details)
            self.assertTrue(os.path.isdir(os.path.join(out, 'José_Núñez_4711')))
            second = grade(students['model'])
            self.assertRegex(second, r'grade: \[1/1\] José Núñez \(4711\): 14 / 14 \(\d+ s\); before 9 / 14: '
                                     r'avoid_stops 0 -> 3, avoid_stays 0 -> 2\n')
            with open(os.path.join(out, 'report.html'), encoding='utf-8') as page:
                self.assertIn('The earlier grading into this folder gave 9 / 14; changed since: avoid_stops 0 → 3, '
                              'avoid_stays 0 → 2.', page.read())


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'test_grade_installed', GradeAsInstalledTest)
