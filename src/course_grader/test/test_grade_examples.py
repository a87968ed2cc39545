#!/usr/bin/env python3
"""grade --no-container on the trusted examples of the example classes (no hostile one): scores and
sentences as expected.yaml says, and the same score on a second run."""
import os
import subprocess
import tempfile
import unittest

import rostest

from example_class import EXAMPLES, expected, labs, mismatches, read_results

# Quick ones, and each kind of outcome: full marks, the slides as printed, a build failure.
TRUSTED = {'move_turtlebot3': ['model', 'slides_as_printed', 'cmake_error'], 'my_turtle': ['slides_as_printed'],
           'ros_exercises': ['model', 'slides_as_printed']}


class GradeExamplesTest(unittest.TestCase):

    def test_trusted_examples_without_containers(self):
        for lab in labs():
            students = [s for s in TRUSTED.get(lab, []) if s in expected(lab)]
            with tempfile.TemporaryDirectory() as folder:
                out = os.path.join(folder, 'grades')
                result = subprocess.run(['rosrun', 'course_grader', 'grade', lab, '--no-container', '--jobs', '2',
                                         '--out', out] + [os.path.join(EXAMPLES, lab, s) for s in students],
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        universal_newlines=True, stdin=subprocess.DEVNULL)
                print(result.stdout)
                self.assertEqual(result.returncode, 0, result.stdout)
                self.assertTrue(result.stdout.startswith('grade: --no-container: NOTHING IS ISOLATED'))
                rows, details = read_results(out)
                self.assertEqual(sorted(rows), sorted(students))
                self.assertEqual(mismatches(lab, rows, details, students), [])


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'test_grade_examples', GradeExamplesTest)
