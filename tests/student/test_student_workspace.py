"""A student, end to end, in fresh terminals: a workspace of their own on top of this one
(tools/new-workspace.sh), `catkin_create_pkg`, the slides' code as printed (slides/; the Python
ones end in .txt, as Python 2 prints are no Python 3 source to check), the failure
it meets and the message docs/copying-the-slides/ quotes for it, the edit the page gives, then
the node working against the simulator.

Every terminal starts from nothing but HOME and a PATH whose first `python`/`python3` is an
interpreter without rospy (as pyenv or conda give), and sources only the student's
devel/setup.bash: what it needs must come from the workspace's environment hooks."""
import os
import re
import shutil
import subprocess
import tempfile

import pytest

from course_common.processes import free_port, stop_process_group
from course_common.waiting import wait_until

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
COURSE_DEVEL = os.path.join(os.environ.get('CATKIN_BUILD_BASE', ROOT), 'devel')
SLIDES = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'slides')
# tools/new-workspace.sh on top of the build folder this test runs with (terminals start from nothing).
NEW_WORKSPACE = 'CATKIN_BUILD_BASE=%s %s/tools/new-workspace.sh' % (os.path.dirname(COURSE_DEVEL), ROOT)
# The messages docs/copying-the-slides/ quotes, as the student sees them.
MISSING_PARENTHESES = "SyntaxError: Missing parentheses in call to 'print'. Did you mean print(...)?"
NO_ROSPY = "ModuleNotFoundError: No module named 'rospy'"
NO_POSE_HEADER = 'fatal error: turtlesim/Pose.h: No such file or directory'
NO_SCREEN = 'rviz needs a screen, and DISPLAY is not set'
POSE_LINE = re.compile(r'x: (\d+\.\d\d), y: (\d+\.\d\d)')


class Student:
    """A home with a workspace in it, and terminals that start from nothing."""

    def __init__(self, home):
        self.home = home
        self.workspace = os.path.join(home, 'catkin_ws')
        # A `python` first on PATH that has no rospy: Debian's own, without its site-packages.
        self.other_python = os.path.join(home, '.pyenv', 'shims')
        os.makedirs(self.other_python)
        for name in ('python', 'python3'):
            shim = os.path.join(self.other_python, name)
            with open(shim, 'w') as script:
                script.write('#!/bin/sh\nexec /usr/bin/python3 -S "$@"\n')
            os.chmod(shim, 0o755)
        self.started = []

    def _argv(self, commands, source=True):
        # ROS_HOME as a user's own terminal has it (HOME/.ros): rospack looks up the home of the
        # passwd entry, not HOME, and would write its caches into the home of whoever runs the tests.
        shell = {'HOME': self.home, 'PATH': self.other_python + ':/usr/local/bin:/usr/bin:/bin',
                 'LANG': 'C.UTF-8', 'ROS_HOME': os.path.join(self.home, '.ros')}
        setup = 'source %s/devel/setup.bash\n' % self.workspace if source else ''
        return (['env', '-i'] + ['%s=%s' % item for item in shell.items()]
                + ['bash', '-c', setup + commands])

    def run(self, commands, timeout=300, source=True):
        """Runs shell commands in a new terminal in the workspace; returns (exit status, output)."""
        done = subprocess.run(self._argv(commands, source), cwd=self.workspace, timeout=timeout,
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, universal_newlines=True)
        return done.returncode, done.stdout

    def start(self, commands, name):
        """Starts shell commands in another new terminal; their output goes to a log (output())."""
        log = open(os.path.join(self.home, '%s-%d.log' % (name, len(self.started))), 'w+')
        process = subprocess.Popen(self._argv(commands), cwd=self.workspace, stdin=subprocess.DEVNULL,
                                   stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        process.log = log
        self.started.append(process)
        return process

    @staticmethod
    def output(process):
        with open(process.log.name) as log:
            return log.read()

    def stop_all(self):
        for process in reversed(self.started):
            stop_process_group(process)
            process.log.close()

    def write(self, path, text):
        path = os.path.join(self.workspace, path)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w') as target:
            target.write(text)
        return path

    def copy_slide(self, slide, path):
        with open(os.path.join(SLIDES, slide)) as source:
            return self.write(path, source.read())

    def edit(self, path, old, new):
        """One edit of docs/copying-the-slides/: `old` must be there."""
        path = os.path.join(self.workspace, path)
        with open(path) as source:
            text = source.read()
        assert old in text, '%s has no %r' % (path, old)
        with open(path, 'w') as target:
            target.write(text.replace(old, new))


def new_student():
    """Someone with a home of their own and a workspace in it, made by tools/new-workspace.sh on top
    of this one (the build folder CATKIN_BUILD_BASE names, if any); and what the script printed."""
    # A folder of its own, not pytest's tmp_path: pytest removes all but the last three of those,
    # and other pytest runs on a shared machine would delete this workspace under the test.
    someone = Student(tempfile.mkdtemp(prefix='student-home-'))
    made = subprocess.run(someone._argv(NEW_WORKSPACE + ' ~/catkin_ws', source=False),
                          cwd=someone.home, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=300)
    assert made.returncode == 0, made.stdout
    return someone, made.stdout


def test_the_new_workspace_gives_the_course_environment(student):
    status, output = student.run('command -v python; python -c "import rospy; print(rospy.__file__)"; '
                                 'echo "$ROS_HOSTNAME|$LD_PRELOAD"; rospack find turtlesim')
    assert status == 0, output
    lines = output.splitlines()
    assert lines[0] == '/usr/bin/python'
    assert lines[1].startswith('/usr/lib/python3/dist-packages/rospy/')
    assert lines[2] == 'localhost|%s/lib/libros_loopback.so' % COURSE_DEVEL
    assert lines[3] == os.path.join(ROOT, 'src', 'turtlesim')


def test_bad_folders_get_a_clear_error(student):
    status, output = student.run(NEW_WORKSPACE + ' /etc/hostname', source=False)
    assert status == 1 and 'exists and is not a folder' in output
    status, output = student.run(NEW_WORKSPACE + ' ~', source=False)
    assert status == 1 and 'is not empty and has no src/' in output


def test_move_turtlebot3_laser_data_as_printed_then_edited(student):
    # rospack profile: rospack remembers packages for 60 s, so right after catkin_create_pkg it would
    # still find the course's package of that name (docs/student-workspace.md says so).
    status, output = student.run('cd src && catkin_create_pkg move_turtlebot3 rospy geometry_msgs sensor_msgs && rospack profile')
    assert status == 0 and 'Successfully created files' in output, output
    for script in ('trajectory.py', 'laser_data.py'):
        student.copy_slide(script + '.txt', 'src/move_turtlebot3/scripts/' + script)
    status, output = student.run('chmod +x src/move_turtlebot3/scripts/*.py && catkin_make')
    assert status == 0, output[-3000:]

    # Without the workspace sourced, `#! /usr/bin/env python` finds the python without rospy.
    status, output = student.run('src/move_turtlebot3/scripts/trajectory.py', source=False)
    assert status == 1 and output.rstrip().endswith(NO_ROSPY), output
    # With it: Debian's python, and the slide's Python 2 prints stop it.
    status, output = student.run('rosrun move_turtlebot3 laser_data.py')
    assert status == 1 and output.rstrip().endswith(MISSING_PARENTHESES), output
    assert re.search(r'laser_data\.py", line 7\n +print msg\.ranges\[0\]', output), output

    # The page's edit: print msg.ranges[N] -> print(msg.ranges[N]).
    for beam in (0, 90, 180, 270, 359):
        student.edit('src/move_turtlebot3/scripts/laser_data.py',
                     'print msg.ranges[%d]' % beam, 'print(msg.ranges[%d])' % beam)
    port = free_port()
    master = 'export ROS_MASTER_URI=http://localhost:%d; ' % port
    student.start(master + 'exec roslaunch -p %d turtlebot3_gazebo turtlebot3_world.launch' % port, 'world')
    # Unbuffered, as Python writes to a terminal: into a log it would print in blocks of 8 kB (27 s of scans).
    laser = student.start(master + 'export PYTHONUNBUFFERED=1; exec rosrun move_turtlebot3 laser_data.py',
                          'laser_data')
    block = re.compile(r'==========\ns1 \[0\]\n(\S+)\ns2 \[90\]\n(\S+)\ns3 \[180\]\n(\S+)\n'
                       r's4 \[270\]\n(\S+)\ns5 \[359\]\n(\S+)\n')
    wait_until(lambda: len(block.findall(student.output(laser))) >= 3, 120,
               'laser_data.py to print three scans')
    ranges = [float(value) for value in block.findall(student.output(laser))[-1]]
    # turtlebot3_world from (-2, -0.5): the wall is 1.08 m to the right, a pillar row 2.05 m left.
    assert ranges[3] == pytest.approx(1.08, abs=0.05), ranges
    assert ranges[1] == pytest.approx(2.05, abs=0.05), ranges
    assert all(0.12 <= value <= 3.5 or value == float('inf') for value in ranges), ranges
    for process in student.started[-2:]:
        stop_process_group(process)


def test_rviz_without_a_screen_says_what_to_do(student):
    port = free_port()
    status, output = student.run('unset DISPLAY; export ROS_MASTER_URI=http://localhost:%d; '
                                 'roslaunch -p %d turtlebot3_gazebo turtlebot3_gazebo_rviz.launch'
                                 % (port, port), timeout=120)
    assert NO_SCREEN in output and 'xvfb-run -a roslaunch turtlebot3_gazebo' in output, output
    assert 'could not connect to display' not in output


def test_my_turtle_as_printed_then_edited(student):
    status, output = student.run('cd src && catkin_create_pkg my_turtle std_msgs rospy roscpp && rospack profile')
    assert status == 0 and 'Successfully created files' in output, output
    student.copy_slide('CMakeLists_my_turtle.txt', 'src/my_turtle/CMakeLists.txt')
    student.copy_slide('move_turtle.launch', 'src/my_turtle/launch/move_turtle.launch')
    student.copy_slide('my_turtle_node_stage1.cpp', 'src/my_turtle/src/my_turtle_node.cpp')
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]
    # The slide runs its launch file with rosrun.
    status, output = student.run('rosrun my_turtle move_turtle.launch')
    assert status != 0
    assert "[rosrun] Couldn't find executable named move_turtle.launch below %s/src/my_turtle" % (
        student.workspace) in output, output

    # Stage 2: the pose subscriber needs turtlesim's headers, which the slide's CMakeLists lacks.
    student.copy_slide('my_turtle_node_stage2.cpp', 'src/my_turtle/src/my_turtle_node.cpp')
    status, output = student.run('catkin_make')
    assert status != 0 and NO_POSE_HEADER in output, output[-3000:]
    student.edit('src/my_turtle/CMakeLists.txt', '  std_msgs\n)', '  std_msgs\n  geometry_msgs\n  turtlesim\n)')
    student.edit('src/my_turtle/package.xml', '  <exec_depend>std_msgs</exec_depend>',
                 '  <exec_depend>std_msgs</exec_depend>\n  <depend>geometry_msgs</depend>\n'
                 '  <depend>turtlesim</depend>')
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]

    port = free_port()
    launched = student.start('export ROS_MASTER_URI=http://localhost:%d; '
                             'exec roslaunch -p %d my_turtle move_turtle.launch' % (port, port), 'my_turtle')

    def poses():
        return [(float(x), float(y)) for x, y in POSE_LINE.findall(student.output(launched))]

    # 0.5 m/s along +x from turtlesim's centre (5.54, 5.54), printing every pose, as on the slide.
    wait_until(lambda: len(poses()) > 20 and poses()[-1][0] > 6.0, 60, 'turtle1 to pass x=6.0')
    assert all(y == 5.54 for _, y in poses()), poses()[-5:]
    assert poses()[0][0] < poses()[-1][0]
    stop_process_group(launched)

    # The project's own my_turtle is shadowed by the student's, in this terminal...
    status, output = student.run('rospack find my_turtle; roslaunch my_turtle move_pose.launch')
    assert output.splitlines()[0] == os.path.join(student.workspace, 'src', 'my_turtle')
    assert 'RLException: [move_pose.launch] is neither a launch file in package [my_turtle]' in output
    # ... and reached by sourcing the course's own devel/setup.bash (docs/student-workspace.md).
    status, output = student.run('source %s/setup.bash; rospack find my_turtle; '
                                 'roslaunch --files my_turtle move_pose.launch' % COURSE_DEVEL)
    assert status == 0, output
    assert output.splitlines()[0] == os.path.join(ROOT, 'src', 'my_turtle')
    # Stage 3 (its error, the page's edit, full marks): test_pages_my_turtle.py.


def test_the_slides_are_copied_as_printed():
    """The slides/ files keep the errors the pages are about (a tidier copy would test nothing)."""
    with open(os.path.join(SLIDES, 'laser_data.py.txt')) as script:
        assert script.read().count('print msg.ranges[') == 5
    with open(os.path.join(SLIDES, 'CMakeLists_my_turtle.txt')) as cmake:
        assert 'turtlesim' not in cmake.read()
    assert shutil.which('catkin_create_pkg'), 'catkin_create_pkg (python3-catkin-pkg) is missing'
