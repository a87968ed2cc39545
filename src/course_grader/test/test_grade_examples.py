#!/usr/bin/env python3
"""grade --no-container on the trusted examples of the example classes (no hostile one): scores and
sentences as expected.yaml says, and nothing the grading started still running afterwards."""
import os
import signal
import subprocess
import tempfile
import unittest

import rostest

from course_testing.process_table import command_line, marked_processes, new_mark, stop_marked, with_mark
from course_testing.waiting import wait_until
from example_class import EXAMPLES, expected, labs, make_class, mismatches, read_results

# Quick ones, and each kind of outcome: full marks, the slides as printed, a build failure.
TRUSTED = {'move_turtlebot3': ['model', 'slides_as_printed', 'cmake_error'], 'my_turtle': ['slides_as_printed'],
           'ros_exercises': ['model', 'slides_as_printed']}


def tagged_processes(tag):
    """The command lines of the processes whose environment carries tag (all that a command given
    it started)."""
    return [command_line(pid) for pid in marked_processes(tag)]


class GradeExamplesTest(unittest.TestCase):

    def test_trusted_examples_without_containers(self):
        tag = new_mark('COURSE_GRADER_TEST')
        for lab in labs():
            students = [s for s in TRUSTED.get(lab, []) if s in expected(lab)]
            with tempfile.TemporaryDirectory() as folder:
                out = os.path.join(folder, 'grades')
                submissions = make_class(lab, os.path.join(folder, 'class'))
                result = subprocess.run(['rosrun', 'course_grader', 'grade', lab, '--no-container', '--jobs', '2',
                                         '--out', out] + [submissions[s] for s in students],
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                        stdin=subprocess.DEVNULL, env=with_mark(tag))
                print(result.stdout)
                self.assertEqual(result.returncode, 0, result.stdout)
                self.assertTrue(result.stdout.startswith('grade: --no-container: NOTHING IS ISOLATED'))
                rows, details = read_results(out)
                self.assertEqual(sorted(rows), sorted(students))
                self.assertEqual(mismatches(lab, rows, details, students), [])
                # roscore, fake_tb3, turtlesim, the students' nodes: all gone (roslaunch's nodes
                # run in sessions of their own, which no process group reaches).
                self.assertEqual(tagged_processes(tag), [])

    def test_a_check_stopped_by_sigterm_leaves_nothing_running(self):
        # A student closes the terminal, or kills the check, while roscore and fake_tb3 run: the
        # session, in a session of its own, would go on without it.
        tag = new_mark('COURSE_GRADER_TEST')
        check = subprocess.Popen(['rosrun', 'course_grader', 'check', 'move_turtlebot3',
                                  os.path.join(EXAMPLES, 'move_turtlebot3', 'model'), '--only', 'avoid_stops'],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                 stdin=subprocess.DEVNULL, env=with_mark(tag))
        try:
            wait_until(lambda: any('fake_tb3' in line for line in tagged_processes(tag)), 120,
                       'the check to start fake_tb3')
            check.terminate()
            output = check.communicate(timeout=60)[0]
            left = tagged_processes(tag)
        finally:
            check.kill()
            stop_marked(tag)
        print(output)
        self.assertEqual(left, [])
        self.assertEqual(check.returncode, 128 + signal.SIGTERM, output)


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'test_grade_examples', GradeExamplesTest)
