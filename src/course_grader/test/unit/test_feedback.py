"""Sentences about the usual mistakes, from sources and logs (no ROS)."""
import os

from course_grader import feedback

SLIDE_LASER = '''#! /usr/bin/env python
import rospy
def callback(msg):
    print('s1 [0]')
    print msg.ranges[0]   # front
    print(msg.ranges[90])
    print
    printer = 1
'''


def write(tmp_path, name, text, mode=0o755):
    path = tmp_path / name
    path.write_text(text)
    os.chmod(str(path), mode)
    return str(path)


def test_python2_prints_name_file_line_and_fix(tmp_path):
    path = write(tmp_path, 'laser_data.py', SLIDE_LASER)
    assert feedback.python2_prints(path, 'move_turtlebot3/scripts/laser_data.py') == [
        'move_turtlebot3/scripts/laser_data.py line 5: `print msg.ranges[0]` is Python 2; under Python 3 '
        'print is a function: write `print(msg.ranges[0])`']


def test_script_problems_execute_bit_shebang_and_python2_interpreter(tmp_path):
    assert feedback.script_problems(write(tmp_path, 'good.py', '#!/usr/bin/env python3\n')) == []
    assert feedback.script_problems(write(tmp_path, 'direct.py', '#!/usr/bin/python3\n')) == []
    no_x = feedback.script_problems(write(tmp_path, 'a.py', 'import rospy\n', 0o644))
    assert no_x == ['a.py is not executable: run `chmod +x a.py` (rosrun only starts executable scripts)',
                    'a.py has no #! line: make its first line `#!/usr/bin/env python3`']
    assert feedback.script_problems(write(tmp_path, 'b.py', '#! /usr/bin/env python\n')) == [
        "b.py line 1: `#! /usr/bin/env python` asks for `python`, which this course's ROS does not run "
        "(it runs on Python 3): write `#!/usr/bin/env python3`"]


def test_first_compiler_error_of_gcc_and_of_cmake():
    gcc = ('[ 50%] Building CXX object my_turtle/CMakeFiles/my_turtle_node.dir/src/a.cpp.o\n'
           '/tmp/ws/src/my_turtle/src/my_turtle_node.cpp: In function int main(int, char**):\n'
           '/tmp/ws/src/my_turtle/src/my_turtle_node.cpp:12:5: error: expected ; before ros\n'
           '/tmp/ws/src/my_turtle/src/my_turtle_node.cpp:20:1: error: second\n')
    assert feedback.first_compiler_error(gcc) == \
        'first compiler error: my_turtle/src/my_turtle_node.cpp line 12: expected ; before ros'
    cmake = ('CMake Error at /usr/share/catkin/cmake/catkinConfig.cmake:82 (find_package):\n'
             '  Could not find a package configuration file provided by "geometry_msg" with\n'
             '  any of the following names:\n\n    geometry_msgConfig.cmake\n'
             'Call Stack (most recent call first):\n  move_turtlebot3/CMakeLists.txt:3 (find_package)\n')
    assert feedback.first_compiler_error(cmake) == ('CMake error in move_turtlebot3/CMakeLists.txt line 3: '
                                                    'Could not find a package configuration file provided by '
                                                    '"geometry_msg"')
    assert feedback.first_compiler_error('[100%] Built target x\n') is None
    missing = '/tmp/ws/src/my_turtle/src/n.cpp:3:10: fatal error: turtlesim/Pose.h: No such file or directory\n'
    assert feedback.first_compiler_error(missing) == (
        'first compiler error: my_turtle/src/n.cpp line 3: turtlesim/Pose.h: No such file or directory. The '
        'header comes from the package turtlesim: add turtlesim to find_package(catkin REQUIRED COMPONENTS ...) '
        'in CMakeLists.txt and a <depend>turtlesim</depend> to package.xml')


CRASH = '''[INFO] started
Traceback (most recent call last):
  File "/usr/lib/python3/dist-packages/rospy/topics.py", line 750, in _invoke_callback
    cb(msg)
  File "move_turtlebot3/scripts/laser_data.py", line 9, in callback
    print(msg.range[0])
          ^^^^^^^^^
AttributeError: 'LaserScan' object has no attribute 'range'
[INFO] more
'''


def test_explain_run_crash_never_started_never_stopped_and_python2():
    assert feedback.explain_run('laser_data.py', CRASH, True, True) == [
        'laser_data.py crashed; its last traceback lines:\n'
        '  File "move_turtlebot3/scripts/laser_data.py", line 9, in callback\n    print(msg.range[0])\n'
        '          ^^^^^^^^^\nAttributeError: \'LaserScan\' object has no attribute \'range\'']
    assert feedback.explain_run('t.py', '', False, None) == [
        't.py never started a ROS node (no init_node within the time limit)']
    assert feedback.explain_run('t.py', '', True, False) == [
        't.py did not stop on Ctrl-C (SIGINT) and had to be killed: let rospy.spin() or '
        '`while not rospy.is_shutdown()` end the program']
    syntax = ('  File "/tmp/ws/src/p/scripts/l.py", line 5\n    print msg.ranges[0]\n    ^^^^^\n'
              "SyntaxError: Missing parentheses in call to 'print'. Did you mean print(...)?\n")
    sentences = feedback.explain_run('l.py', syntax, False, None, ['l.py line 5: A', 'l.py line 7: B'])
    assert sentences == ['l.py does not start under Python 3: l.py line 5: A',
                         '1 more Python 2 prints in l.py: lines 7']
    assert feedback.explain_run('l.py', syntax.replace("Missing parentheses in call to 'print'", 'bad'),
                                False, None) == [
        'l.py does not start: SyntaxError in l.py line 5: bad. Did you mean print(...)?']


def test_a_pasted_shebang_indented_or_below_line_one_is_named(tmp_path):
    indented = feedback.script_problems(write(tmp_path, 'laser_data.py', '    #!/usr/bin/env python3\n    import rospy\n'))
    assert indented == ['laser_data.py: its #! line is indented: `    #!/usr/bin/env python3`. A paste from the slides '
                        'moves it; it must be the first line and start in column 1, or the shell runs the file '
                        'instead of Python (`from: command not found`)']
    below = feedback.script_problems(write(tmp_path, 'trajectory.py', '\n#!/usr/bin/env python3\nimport rospy\n'))
    assert below[0].startswith('trajectory.py: its #! line is on line 2, not line 1. A paste')


def test_a_file_the_shell_ran_is_named_with_the_shells_own_line():
    # What Debian 12 prints for a pasted laser_data.py (docs/copying-the-slides/move_turtlebot3.md).
    output = ("import-im6.q16: unable to open X server `' @ error/import.c/ImportImageCommand/346.\n"
              "/home/you/catkin_ws/src/move_turtlebot3/scripts/laser_data.py: line 3: from: command not found\n")
    assert feedback.explain_run('laser_data.py', output, False, True) == [
        "laser_data.py was run by the shell, not by Python (`import-im6.q16: unable to open X server`): make "
        "`#!/usr/bin/env python3` its first line, starting in column 1"]
    debian13 = "/x/scripts/laser_data.py: line 3: from: command not found\n"
    assert feedback.explain_run('laser_data.py', debian13, False, True)[0].startswith(
        'laser_data.py was run by the shell, not by Python (`/x/scripts/laser_data.py: line 3: from: command not found`)')
