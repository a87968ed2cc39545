#!/usr/bin/env python3
"""A slow but honest submission, graded --no-container with a rubric of small limits: its build
takes most of build_seconds, each node most of start_seconds to start, then works, and stops only
when killed after stop_seconds. Every limit used, it still gets each run's own verdict: the wall
limit of the session (course_grader.wall_limit) is the sum of its steps, not less."""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

import rostest

from course_grader import rubric as rubrics
from course_grader.labs import wall_limit_of
from example_class import edited_rubric, make_class

LIMITS = {'build_seconds': 50, 'run_seconds': 14, 'start_seconds': 6, 'stop_seconds': 4}
BUILD_SLEEP = 20   # s of the build's own; catkin_make takes the rest (10 s, 25 s beside a whole suite)
START_SLEEP = 3    # s before each node starts
# Put after `import rospy` in each script: a slow start, and Ctrl-C ignored once the node runs
# (rospy sets its own handler in init_node), so that only the grader's kill stops it.
SLOW = '''import signal, time
time.sleep(%d)
_init_node = rospy.init_node
def _init_and_ignore_ctrl_c(*args, **kwargs):
    _init_node(*args, **kwargs)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
rospy.init_node = _init_and_ignore_ctrl_c
''' % START_SLEEP
SCRIPTS = ('trajectory.py', 'laser_data.py', 'avoid_obstacle.py')
KILLED = 'did not stop on Ctrl-C (SIGINT) and had to be killed'


def slow_model(folder):
    """The model of move_turtlebot3, made slow in `folder`/slow_but_honest."""
    package = os.path.join(folder, 'slow_but_honest')
    shutil.copytree(make_class('move_turtlebot3', os.path.join(folder, 'class'))['model'], package)
    with open(os.path.join(package, 'CMakeLists.txt'), 'a') as stream:
        stream.write('execute_process(COMMAND sleep %d)\n' % BUILD_SLEEP)
    for script in SCRIPTS:
        path = os.path.join(package, 'scripts', script)
        with open(path) as stream:
            text = stream.read()
        with open(path, 'w') as stream:
            stream.write(text.replace('import rospy', 'import rospy\n' + SLOW, 1))
    return package


def small_rubric(folder):
    """move_turtlebot3's rubric with LIMITS."""
    return edited_rubric('move_turtlebot3', os.path.join(folder, 'small_limits.yaml'),
                         lambda data: data.update(limits=LIMITS))


class SlowHonestTest(unittest.TestCase):

    def test_a_submission_that_uses_every_limit_gets_each_runs_verdict(self):
        with tempfile.TemporaryDirectory() as folder:
            package, rubric = slow_model(folder), small_rubric(folder)
            out = os.path.join(folder, 'grades')
            graded = subprocess.run(['rosrun', 'course_grader', 'grade', 'move_turtlebot3', '--no-container',
                                     '--rubric', rubric, '--out', out, package], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, universal_newlines=True, stdin=subprocess.DEVNULL)
            print(graded.stdout)
            self.assertEqual(graded.returncode, 0, graded.stdout)
            with open(os.path.join(out, 'slow_but_honest', 'result.json')) as stream:
                result = json.load(stream)
            with open(os.path.join(out, 'slow_but_honest', 'grader.txt')) as stream:
                print(stream.read())
            print('graded in %.0f s; wall limit %d s' % (result['seconds'], wall_limit_of(rubrics.load(rubric))))
        self.assertIsNone(result.get('error'))
        self.assertEqual(result['score'], result['max_score'], [(c['id'], c['reason']) for c in result['criteria']])
        # Each run ran its course: its node was killed after stop_seconds, and said so.
        for criterion in result['criteria']:
            if criterion['id'] not in ('builds', 'executable'):
                self.assertTrue(any(KILLED in hint for hint in criterion['hints']), criterion)


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'test_slow_honest', SlowHonestTest)
