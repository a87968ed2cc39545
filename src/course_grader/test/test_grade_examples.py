#!/usr/bin/env python3
"""grade --no-container on the trusted examples of the example classes (no hostile code): scores and
sentences as expected.yaml says, and nothing the grading started still running afterwards; and a
Moodle download whose names and archive, not code, are hostile."""
import csv
import json
import os
import shutil
import signal
import subprocess
import tempfile
import unittest
import zipfile

import rostest

from course_common.process_table import command_line, marked_processes, new_mark, stop_marked, with_mark
from course_common.waiting import wait_until
from example_class import EXAMPLES, expected, labs, make_class, mismatches, read_results
from hostile_archive import link_chain_archive, markers_under

# What a build could do to the grading's ROS master (it can reach it): find it among the children of
# the grading session, its ancestor, wait until the grader's own node is on it (the master is up and
# the grader has seen it up), shut it down through the master's API, and end once it has exited.
MASTER_STOPPING_BUILD = """
import os, time, xmlrpc.client
def parent(pid):
    with open('/proc/%d/stat' % pid) as stream:
        return int(stream.read().rsplit(')', 1)[1].split()[1])
def argv(pid):
    with open('/proc/%d/cmdline' % pid, 'rb') as stream:
        return stream.read().decode(errors='replace').split('\\0')
session = os.getppid()
while 'course_grader.grading_session' not in argv(session):
    session = parent(session)
for _ in range(600):
    children = [int(pid) for pid in os.listdir('/proc') if pid.isdigit() and int(pid) != os.getpid()
                and os.path.exists('/proc/' + pid) and parent(int(pid)) == session]
    masters = [(pid, argv(pid)) for pid in children if '--core' in argv(pid)]
    if masters:
        pid, command = masters[0]
        master = xmlrpc.client.ServerProxy('http://localhost:%s' % command[command.index('-p') + 1])
        try:
            state = master.getSystemState('/build')[2]
        except OSError:
            state = []
        if any('/course_grader' in nodes for kind in state for _, nodes in kind):
            master.shutdown('/build', 'the build stops the master')
            while os.path.exists('/proc/%d' % pid) and argv(pid) != ['']:   # a zombie has no command line
                time.sleep(0.05)
            break
    time.sleep(0.1)
"""

# Quick ones, and each kind of outcome: full marks, the slides as printed, a build failure; and the
# judge's doors that need no container (they only publish or print: a sender that says it is
# fake_tb3, a laser block printed from a stored log, a drive by the clock). The
# ros_exercises model (a link to src/ros_exercises) gets its 18 in tests/student/
# test_pages_ros_exercises.py, which grades those files with Fig. 5 pasted as circle.cpp and edited
# as its page says: a grading of the same package here would cost a build and six runs again.
TRUSTED = {'move_turtlebot3': ['model', 'slides_as_printed', 'cmake_error', 'hostile_forged_sender', 'hostile_stored_scan',
                                'timed_drive'],
           'my_turtle': ['slides_as_printed'],
           'ros_exercises': ['slides_as_printed']}


# The runs each lab keeps as a bag, and topics each bag must hold with at least one message
# (course_grader.bags); a submission that does not build has none.
BAGS = {'move_turtlebot3': {name: ['/odom', '/scan', '/collisions', '/fake_tb3/run']
                            for name in ('trajectory', 'laser_data', 'avoid_obstacle')},
        'my_turtle': {'move_turtle': ['/turtle1/pose', '/turtle1/cmd_vel', '/turtlesim_node/canvas',
                                      '/turtlesim_node/turtles']},
        # exercise1.launch declares no turtlesim: no simulator, no bag.
        'ros_exercises': dict({'exercise%d' % n: ['/turtle1/pose', '/turtlesim/canvas', '/turtlesim/turtles']
                               for n in (2, 3)}, exercise4=['/robotics/pose', '/turtlesim/service_calls'],
                              **{'exercise5_' + shape: ['/robotics/pose', '/robotics/cmd_vel']
                                 for shape in ('square', 'triangle')})}


def kept_runs(folder):
    """{run: {topic: message count}} of each bag in a student's folder, read as `rosbag info` reads
    it, and the runs with marks beside their bag."""
    import rosbag
    runs, marked = {}, set()
    for name in sorted(os.listdir(folder)):
        if name.endswith('.bag'):
            assert os.path.getsize(os.path.join(folder, name)) < 2 * 2 ** 20, name   # bounded (bags.MAX_MESSAGES)
            with rosbag.Bag(os.path.join(folder, name)) as bag:
                runs[name[:-4]] = {topic: info.message_count
                                   for topic, info in bag.get_type_and_topic_info().topics.items()}
        elif name.endswith('.marks.json'):
            with open(os.path.join(folder, name)) as stream:
                assert all(set(mark) == {'t', 'what', 'criterion'} for mark in json.load(stream))
            marked.add(name[:-len('.marks.json')])
    return runs, marked


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
                # Each run kept as a bag of the simulator's topics, the moments judged beside it.
                for student in students:
                    runs, marked = kept_runs(os.path.join(out, details[student]['folder']))
                    built = next(c['passed'] for c in details[student]['criteria'] if c['id'] == 'builds')
                    wanted = BAGS[lab] if built else {}
                    self.assertEqual(sorted(runs), sorted(wanted), student)
                    for run, topics in wanted.items():
                        self.assertEqual([topic for topic in topics if not runs[run].get(topic)], [],
                                         '%s %s: %s' % (student, run, runs[run]))
                    self.assertLessEqual(marked, set(runs), student)
                # roscore, fake_tb3, turtlesim, the students' nodes: all gone (roslaunch's nodes
                # run in sessions of their own, which no process group reaches).
                self.assertEqual(tagged_processes(tag), [])

    def test_hostile_names_and_a_link_chain_upload_from_moodle(self):
        """A name that is a spreadsheet formula, handing in into_the_wall inside issue 31's link
        chain, and a name with a line break and an escape sequence: nothing is written outside the
        unpacking folder, no more than the twin's score, the cell is text, one line per student."""
        tag = new_mark('COURSE_GRADER_TEST')
        with tempfile.TemporaryDirectory() as folder:
            package = os.path.join(make_class('move_turtlebot3', os.path.join(folder, 'class'))['into_the_wall'],
                                   'move_turtlebot3')
            formula = os.path.join(folder, 'moodle', '=HYPERLINK("x.example","Alice")_4712_assignsubmission_file_')
            escapes = os.path.join(folder, 'moodle', 'Ann\x1b[31m\nLee_4713_assignsubmission_file_')
            for upload in (formula, escapes):
                os.makedirs(upload)
            link_chain_archive(os.path.join(formula, 'catkin_ws.tar.gz'), package)
            with zipfile.ZipFile(os.path.join(escapes, 'report.zip'), 'w') as report:   # no package in it
                report.writestr('report.txt', 'my report')
            # The grader unpacks in the temporary folder: an unpacker that writes through the links
            # leaves the marker there, beside its scratch folder (removed after each student).
            temporary = os.path.join(folder, 'tmp')
            os.makedirs(temporary)
            out = os.path.join(folder, 'grades')
            result = subprocess.run(['rosrun', 'course_grader', 'grade', 'move_turtlebot3', '--no-container', '--jobs',
                                     '2', '--out', out, formula, escapes], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, universal_newlines=True, stdin=subprocess.DEVNULL,
                                    env=dict(with_mark(tag), TMPDIR=temporary))
            print(result.stdout)
            self.assertEqual(result.returncode, 0, result.stdout)
            self.assertEqual(markers_under(folder), [])
            self.assertEqual(tagged_processes(tag), [])
            with open(os.path.join(out, 'grades.csv'), encoding='utf-8', newline='') as stream:
                rows = {row['id']: row for row in csv.DictReader(stream)}
        self.assertEqual(rows['4712']['student'], '\'=HYPERLINK("x.example","Alice")')
        self.assertLessEqual(float(rows['4712']['score']), expected('move_turtlebot3')['into_the_wall']['score'])
        self.assertEqual(rows['4713']['student'], 'Ann\x1b[31m\nLee')   # the name as Moodle wrote it
        lines = [line for line in result.stdout.splitlines() if line.startswith('grade: [')]
        self.assertEqual(len(lines), 2, result.stdout)
        self.assertIn('] =HYPERLINK("x.example","Alice") (4712): ', '\n'.join(lines))
        self.assertRegex('\n'.join(lines), r'\] Ann\\x1b\[31m\\nLee \(4713\): 0 / 14 \(\d+ s\): no package named move_')
        self.assertNotIn('\x1b', result.stdout)

    def test_a_build_that_stops_the_master_gets_no_run_and_says_why(self):
        with tempfile.TemporaryDirectory() as folder:
            model = make_class('move_turtlebot3', os.path.join(folder, 'class'))['model']
            package = os.path.join(folder, 'master_stopper')   # the package's folder, named after the student
            shutil.copytree(model, package)
            with open(os.path.join(package, 'stop_master.py'), 'w') as stream:
                stream.write(MASTER_STOPPING_BUILD)
            with open(os.path.join(package, 'CMakeLists.txt'), 'a') as stream:
                stream.write('execute_process(COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/stop_master.py)\n')
            out = os.path.join(folder, 'grades')
            result = subprocess.run(['rosrun', 'course_grader', 'grade', 'move_turtlebot3', '--no-container',
                                     '--out', out, package], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, universal_newlines=True, stdin=subprocess.DEVNULL)
            print(result.stdout)
            self.assertEqual(result.returncode, 0, result.stdout)
            with open(os.path.join(out, 'master_stopper', 'result.json')) as stream:
                graded = json.load(stream)
        sentence = 'not run: the ROS master stopped during the build'
        self.assertEqual(graded['error'], sentence)
        self.assertIn('master_stopper: 2 / 14', result.stdout)   # it builds, its scripts are executable
        self.assertEqual({c['id']: c['reason'] for c in graded['criteria'] if not c['passed']},
                         {criterion: sentence for criterion in ('trajectory_rate', 'trajectory_circle',
                                                                'laser_data', 'avoid_stops', 'avoid_stays')})

    def private_folders(self):
        """TMPDIR and ROS_HOME of a check of the test's own, removed after the test."""
        folder = tempfile.mkdtemp(prefix='check-test-')
        self.addCleanup(shutil.rmtree, folder, True)
        for name in ('tmp', 'ros_home'):
            os.mkdir(os.path.join(folder, name))
        return {'TMPDIR': os.path.join(folder, 'tmp'), 'ROS_HOME': os.path.join(folder, 'ros_home')}

    def test_a_check_leaves_nothing_in_the_temporary_folder(self):
        # Its session's folders, its scratch workspace, and genpy's folders for the messages of the
        # replays' bags (removed by genpy at the check's exit).
        folders = self.private_folders()
        check = subprocess.run(['rosrun', 'course_grader', 'check', 'move_turtlebot3',
                                os.path.join(EXAMPLES, 'move_turtlebot3', 'model')], stdin=subprocess.DEVNULL,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                               env=dict(os.environ, **folders), timeout=300)
        self.assertEqual(check.returncode, 0, check.stdout)
        self.assertIn('check: total 14 / 14', check.stdout)
        self.assertEqual(os.listdir(folders['TMPDIR']), [])

    def test_a_check_stopped_by_sigterm_leaves_nothing_running(self):
        # A student closes the terminal, or kills the check, while roscore and fake_tb3 run: the
        # session, in a session of its own, would go on without it.
        tag = new_mark('COURSE_GRADER_TEST')
        folders = self.private_folders()
        check = subprocess.Popen(['rosrun', 'course_grader', 'check', 'move_turtlebot3',
                                  os.path.join(EXAMPLES, 'move_turtlebot3', 'model'), '--only', 'avoid_stops'],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                 stdin=subprocess.DEVNULL, env=with_mark(tag, dict(os.environ, **folders)))
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
        self.assertEqual(os.listdir(folders['TMPDIR']), [])


if __name__ == '__main__':
    rostest.rosrun('course_grader', 'test_grade_examples', GradeExamplesTest)
