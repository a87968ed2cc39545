#!/usr/bin/env python3
"""rostest: fake_tb3 started with bad parameters ends at once with a clear error and exit status 1."""
import subprocess
import unittest

import rostest

from course_common.processes import together

CASES = [(['_model:=burgr'], "unknown TurtleBot3 model 'burgr'"),
         (['_world:=moon'], "no world 'moon'"),
         (['_real_time_factor:=-2'], 'real_time_factor must be positive'),
         (['_x_pos:=left'], 'parameter x_pos must be a number'),
         (['_noise_stddev:=-1'], 'parameter noise_stddev must be a finite number >= 0'),
         (['_robots:=[3]'], 'parameter robots must be a list of mappings'),
         (['_robots:=[{name: a}, {name: a}]'], 'robot names must differ, got a, a'),
         (['_robots:=[{name: tb3/0}]'], "every robot needs a name made of letters")]


class BadParametersTest(unittest.TestCase):

    def test_bad_parameters_are_clear_errors(self):
        runs = {}

        def start(index, arguments):
            # A node name per case: private parameters set by `_name:=` stay on the server.
            def run():
                argv = ['rosrun', 'fake_tb3', 'fake_tb3_node', '__name:=bad_fake_tb3_%d' % index] + arguments
                runs[index] = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60,
                                             universal_newlines=True)
            return run
        # All at once: each spends most of its second or two starting and shutting down rospy.
        together(*[start(index, arguments) for index, (arguments, _) in enumerate(CASES)])
        for index, (arguments, message) in enumerate(CASES):
            self.assertEqual(runs[index].returncode, 1, (arguments, runs[index].stdout))
            self.assertIn(message, runs[index].stdout)


if __name__ == '__main__':
    rostest.rosrun('fake_tb3', 'bad_parameters', BadParametersTest)
