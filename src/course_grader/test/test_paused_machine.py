#!/usr/bin/env python3
"""The move_turtlebot3 model graded --no-container with the machine paused 1.5 s between a scan
and laser_data.py's block of it: the processes on the grading's ROS master (fake_tb3) stopped, as
a virtual machine descheduled or a host swapping would stop them, while the node waits. The block is
printed 1.5 s after its scan, later than print_window's second of wall time, but no scan was sent
meanwhile: laser_data gets its 3 points (it got none when the window was wall time only)."""
import os
import re
import subprocess
import tempfile
import unittest

import rostest

from example_class import edited_rubric, make_class, read_results

PAUSE = 1.5   # wall seconds the machine is paused, more than print_window
# Put before laser_data.py's init_node, its callback renamed the_slides_callback: on the third
# scan, before its block is printed, every other process on this node's ROS master is stopped
# PAUSE seconds while this one waits, and their command lines are written to the file named.
PAUSE_THE_MACHINE = '''def pause_the_machine():
    import os, subprocess
    from course_common.process_table import command_line, marked_processes
    stopped = marked_processes('ROS_MASTER_URI=' + os.environ['ROS_MASTER_URI'])
    listed = ' '.join(map(str, stopped))
    subprocess.run(['sh', '-c', 'kill -s STOP %%s; sleep %s; kill -s CONT %%s' %% (listed, listed)])
    with open(%r, 'w') as stream:
        stream.write('\\n'.join(map(command_line, stopped)))


scans_heard = [0]


def callback(msg):
    scans_heard[0] += 1
    if scans_heard[0] == 3:
        pause_the_machine()
    the_slides_callback(msg)


'''


def paused_model(folder, paused_list):
    """The model of move_turtlebot3 in `folder`/paused_machine, its laser_data.py pausing the machine."""
    package = os.path.join(folder, 'paused_machine')
    os.rename(make_class('move_turtlebot3', os.path.join(folder, 'class'))['model'], package)
    path = os.path.join(package, 'scripts', 'laser_data.py')
    with open(path) as stream:
        text = stream.read()
    callback, init = 'def callback(msg):', 'rospy.init_node('
    assert callback in text and init in text, 'the model\'s laser_data.py has no %r or no %r' % (callback, init)
    with open(path, 'w') as stream:
        stream.write(text.replace(callback, 'def the_slides_callback(msg):', 1)
                     .replace(init, PAUSE_THE_MACHINE % (PAUSE, paused_list) + init, 1))
    return package


def laser_rubric(folder):
    """move_turtlebot3's rubric with its laser_data criterion only (and the build's): the others
    have 0 points, which leaves them out."""
    def laser_only(data):
        for criterion in data['criteria']:
            if criterion['id'] not in ('builds', 'executable', 'laser_data'):
                criterion['points'] = 0
    return edited_rubric('move_turtlebot3', os.path.join(folder, 'laser_only.yaml'), laser_only)


class PausedMachineTest(unittest.TestCase):

    def test_a_machine_paused_between_a_scan_and_its_block_costs_laser_data_nothing(self):
        with tempfile.TemporaryDirectory() as folder:
            paused_list = os.path.join(folder, 'paused.txt')
            package, rubric = paused_model(folder, paused_list), laser_rubric(folder)
            out = os.path.join(folder, 'grades')
            graded = subprocess.run(['rosrun', 'course_grader', 'grade', 'move_turtlebot3', '--no-container',
                                     '--rubric', rubric, '--out', out, package], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, universal_newlines=True, stdin=subprocess.DEVNULL)
            self.assertEqual(graded.returncode, 0, graded.stdout)
            result = read_results(out)[1]['paused_machine']
            with open(paused_list) as stream:
                paused = stream.read()
        print('paused:\n' + paused)
        laser = next(c for c in result['criteria'] if c['id'] == 'laser_data')
        self.assertIn('fake_tb3', paused, 'the simulator was not among the processes paused')
        self.assertEqual(laser['points'], laser['max_points'], laser['reason'])
        lags = re.search(r'printed ([\d.]+) to ([\d.]+) ms after it was sent', laser['reason'])
        self.assertTrue(lags and float(lags.group(2)) > 1000 * PAUSE,
                        'the pause did not fall between a scan and its block: %s' % laser['reason'])


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'test_paused_machine', PausedMachineTest)
