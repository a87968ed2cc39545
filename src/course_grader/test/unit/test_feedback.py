"""Sentences about the usual mistakes, from sources and logs (no ROS)."""
import os
import re

from course_grader import feedback
from course_testing.markdown import heading_anchors

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


def test_script_problems_execute_bit_shebang_and_python2_interpreter(tmp_path, monkeypatch):
    assert feedback.script_problems(write(tmp_path, 'good.py', '#!/usr/bin/env python3\n')) == []
    assert feedback.script_problems(write(tmp_path, 'direct.py', '#!/usr/bin/python3\n')) == []
    no_x = feedback.script_problems(write(tmp_path, 'a.py', 'import rospy\n', 0o644), package='move_turtlebot3')
    assert no_x == ['a.py is not executable: run `chmod +x a.py` (rosrun only starts executable scripts: see '
                    'docs/copying-the-slides/move_turtlebot3.md#chmod-x; a folder that Docker mounts from Windows '
                    'or macOS can lose the bit: see docs/student-docker.md#lost-executable-bits)',
                    'a.py has no #! line: make its first line `#!/usr/bin/env python3`']
    # `python`: what it is on this machine is said as it is (python-is-python3 links it to python3.X).
    python = tmp_path / 'bin' / 'python'
    python.parent.mkdir()
    python.symlink_to('python3.11')
    monkeypatch.setattr(feedback.shutil, 'which', lambda command: str(python) if command == 'python' else None)
    slide = write(tmp_path, 'b.py', '#! /usr/bin/env python\n')
    assert feedback.script_problems(slide, package='move_turtlebot3') == [
        "b.py line 1: `#! /usr/bin/env python` asks for `python`, not `python3`: it runs here (`python` is "
        "Python 3 on this machine), but the lab's rubric gives this point only to a #! line that names `python3`: "
        "write `#!/usr/bin/env python3` (see docs/copying-the-slides/move_turtlebot3.md"
        "#python3-not-python-in-the-first-line)"]
    python.unlink()
    python.symlink_to('python2.7')
    assert feedback.script_problems(slide) == [
        "b.py line 1: `#! /usr/bin/env python` asks for `python`, not `python3`: the lab's rubric gives this "
        "point only to a #! line that names `python3`: write `#!/usr/bin/env python3`"]
    monkeypatch.setattr(feedback.shutil, 'which', lambda command: None)
    assert feedback.script_problems(slide) == [
        "b.py line 1: `#! /usr/bin/env python` asks for `python`, which this machine does not have (rosrun "
        "says `env: 'python': No such file or directory`): write `#!/usr/bin/env python3`"]


def test_windows_line_endings_are_named_with_what_rosrun_says(tmp_path):
    crlf = write(tmp_path, 'trajectory.py', '#!/usr/bin/env python3\r\nimport rospy\r\n')
    assert feedback.script_problems(crlf) == [
        "trajectory.py has Windows line endings (CRLF): rosrun stops at its #! line with `env: "
        "'python3\\r': No such file or directory`; convert the file with `sed -i 's/\\r$//' trajectory.py` "
        "(see docs/student-docker.md#windows-line-endings)"]
    # bookworm's env (named as the #! line calls it), then trixie's (`env`); both add a hint about -S.
    for said in ("/usr/bin/env: 'python3\\r': No such file or directory\n",
                 "/bin/env: 'python3\\r': No such file or directory\n",
                 "env: 'python3\\r': No such file or directory\nenv: use -[v]S to pass options in shebang lines\n"):
        assert feedback.explain_run('move_turtlebot3/scripts/t.py', said, False, None) == [
            "move_turtlebot3/scripts/t.py does not start: `%s`: the file has Windows line endings (CRLF), and its "
            "#! line asks for `python3` and a carriage return; convert the file with `sed -i 's/\\r$//' "
            "move_turtlebot3/scripts/t.py` (see docs/student-docker.md#windows-line-endings)" % said.splitlines()[0]]


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
        'in CMakeLists.txt and a <depend>turtlesim</depend> to package.xml '
        '(see docs/copying-the-slides/my_turtle.md#turtlesimposeh-no-such-file-or-directory)')
    # A package with no copying page: no page named.
    assert feedback.first_compiler_error(missing.replace('my_turtle', 'other')).endswith('to package.xml')


def test_the_build_errors_a_paste_of_the_slides_makes_name_their_section():
    # As gcc prints them for the pages' pastes (docs/copying-the-slides/my_turtle.md, ros_exercises.md).
    undeclared = ('/home/you/catkin_ws/src/my_turtle/src/my_turtle_node.cpp:13:5: error: \u2018lin_vel_\u2019 was '
                  'not declared in this scope\n')
    assert feedback.first_compiler_error(undeclared) == (
        'first compiler error: my_turtle/src/my_turtle_node.cpp line 13: \u2018lin_vel_\u2019 was not declared in '
        'this scope (see docs/copying-the-slides/my_turtle.md#lin_vel_-was-not-declared)')
    fig5 = '/home/you/catkin_ws/src/ros_exercises/src/circle.cpp:3:10: error: #include expects "FILENAME" or <FILENAME>\n'
    assert feedback.first_compiler_error(fig5).endswith(
        '<FILENAME> (see docs/copying-the-slides/ros_exercises.md#what-a-paste-of-fig-5-does-first)')
    for typo in ("\u2018geonetry_msgs\u2019 was not declared in this scope", "\u2018Spin\u2019 is not a member of "
                 "\u2018ros\u2019; did you mean \u2018spin\u2019?", "\u2018turtlesim\u2019 does not name a type"):
        assert feedback.first_compiler_error(fig5.replace('#include expects "FILENAME" or <FILENAME>', typo)).endswith(
            '(see docs/copying-the-slides/ros_exercises.md#what-a-paste-of-fig-5-does-first)'), typo
    reset = ('CMake Error at /usr/share/catkin/cmake/catkinConfig.cmake:82 (find_package):\n'
             '  Could not find a package configuration file provided by "roscppreset" with\n'
             '  any of the following names:\n\nCall Stack (most recent call first):\n'
             '  my_turtle/CMakeLists.txt:10 (find_package)\n')
    assert feedback.first_compiler_error(reset) == (
        'CMake error in my_turtle/CMakeLists.txt line 10: Could not find a package configuration file provided by '
        '"roscppreset" (see docs/copying-the-slides/my_turtle.md#what-a-paste-from-the-slides-does-first)')
    assert feedback.paste_run_error('ros_exercises', '[FATAL] [1.2]: You must call ros::init() before creating the '
                                    'first NodeHandle\n') == (
        'a node stopped at once: `You must call ros::init() before creating the first NodeHandle` (Fig. 5 has no '
        '`ros::init`): make `ros::init(argc, argv, "NAME");` the first line of its main '
        '(see docs/copying-the-slides/ros_exercises.md#what-a-paste-of-fig-5-does-first)')
    assert feedback.paste_run_error('ros_exercises', '[ INFO] [1.2]: Turtle subscriber@(5.5, 5.5, 0.0]').startswith(
        'its lines say `Turtle subscriber@(...]`')
    assert feedback.paste_run_error('my_turtle', 'You must call ros::init() before creating the first NodeHandle') \
        is None


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
    # Killed during the run (the kernel's out-of-memory killer takes the student's processes first);
    # any other end before the grader's Ctrl-C (a crash, exit 1) says nothing of the kind.
    assert feedback.explain_run('a.py', '', True, True, exit_before_stop=-9) == [
        'a.py was killed (SIGKILL) during the run, not by the grader: the kernel does this when memory runs '
        'out. Does it keep everything it receives, or start processes without end?']
    assert feedback.explain_run('a.py', '', False, None, exit_before_stop=-9) == [
        'a.py was killed (SIGKILL) before it started a ROS node, not by the grader: the kernel does this when '
        'memory runs out. Does it keep everything it receives, or start processes without end?']
    assert feedback.explain_run('a.py', '', True, True, exit_before_stop=1) == []
    assert feedback.explain_run('a.py', '', False, None, exit_before_stop=1) == [
        'a.py never started a ROS node (no init_node within the time limit)']
    assert feedback.explain_run('a.py', '', True, True, exit_before_stop=None) == []
    syntax = ('  File "/tmp/ws/src/p/scripts/l.py", line 5\n    print msg.ranges[0]\n    ^^^^^\n'
              "SyntaxError: Missing parentheses in call to 'print'. Did you mean print(...)?\n")
    sentences = feedback.explain_run('l.py', syntax, False, None, ['l.py line 5: A', 'l.py line 7: B'])
    assert sentences == ['l.py does not start under Python 3: l.py line 5: A',
                         '1 more Python 2 prints in l.py: lines 7']
    assert feedback.explain_run('l.py', syntax.replace("Missing parentheses in call to 'print'", 'bad'),
                                False, None) == [
        'l.py does not start: SyntaxError in l.py line 5: bad. Did you mean print(...)?']


def test_a_pasted_shebang_indented_or_below_line_one_is_named(tmp_path):
    pasted = write(tmp_path, 'laser_data.py', '    #!/usr/bin/env python3\n    import rospy\n')
    indented = feedback.script_problems(pasted, package='move_turtlebot3')
    assert indented == ['laser_data.py: its #! line is indented: `    #!/usr/bin/env python3`. A paste from the slides '
                        'moves it; it must be the first line and start in column 1, or bash runs the file instead '
                        'of Python (`import: unable to open X server`, `from: command not found`) '
                        '(see docs/copying-the-slides/move_turtlebot3.md#1-the-whole-paste-indented)']
    below = feedback.script_problems(write(tmp_path, 'trajectory.py', '\n#!/usr/bin/env python3\nimport rospy\n'))
    assert below[0].startswith('trajectory.py: its #! line is on line 2, not line 1. A paste')


def test_a_file_the_shell_ran_is_named_with_the_shells_own_line():
    # What Debian 12 prints for a pasted laser_data.py (docs/copying-the-slides/move_turtlebot3.md).
    output = ("import-im6.q16: unable to open X server `' @ error/import.c/ImportImageCommand/346.\n"
              "/home/you/catkin_ws/src/move_turtlebot3/scripts/laser_data.py: line 3: from: command not found\n")
    assert feedback.explain_run('laser_data.py', output, False, True) == [
        "laser_data.py was run by the shell, not by Python (`import-im6.q16: unable to open X server`): its #! "
        "line is not the first line (a paste from the slides moves it): make `#!/usr/bin/env python3` its first "
        "line, starting in column 1, and move every line left by the paste's indentation"]
    debian13 = "/x/scripts/laser_data.py: line 3: from: command not found\n"
    assert feedback.explain_run('laser_data.py', debian13, False, True)[0].startswith(
        'laser_data.py was run by the shell, not by Python (`/x/scripts/laser_data.py: line 3: from: command not found`)')


ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..', '..', '..'))


def python_said(script, line, text, error):
    """What Python 3.11 prints for a file it cannot compile (the caret line left out: 3.13 draws it otherwise)."""
    return '  File "/home/you/catkin_ws/src/%s", line %d\n    %s\n%s\n' % (script, line, text, error)


def test_each_python_error_a_paste_makes_names_its_section(tmp_path):
    """The errors docs/copying-the-slides/move_turtlebot3.md explains, each with its section."""
    see = ' (see docs/copying-the-slides/move_turtlebot3.md#%s)'
    indented = write(tmp_path, 'laser_data.py', '          #! /usr/bin/env python\n          import rospy\n')
    said = python_said('move_turtlebot3/scripts/laser_data.py', 2, 'import rospy',
                       'IndentationError: unexpected indent')
    assert feedback.explain_run('laser_data.py', said, False, None, (), indented, 'move_turtlebot3') == [
        "laser_data.py does not start: Python stops at line 2 with `IndentationError: unexpected indent`, and rosrun "
        "has bash run it (`import: unable to open X server`, `from: command not found`): its #! line is indented: "
        "`          #! /usr/bin/env python` (a paste from the slides moves it): make `#!/usr/bin/env python3` its "
        "first line, starting in column 1, and move every line left by the paste's indentation"
        + see % '1-the-whole-paste-indented']
    cut = write(tmp_path, 'avoid_obstacle.py', "#! /usr/bin/env python\n\nimport rospy\ndef callback(msq):\n"
                "    print('======\n")
    said = python_said('avoid_obstacle.py', 5, "print('======",
                       'SyntaxError: unterminated string literal (detected at line 5)')
    assert feedback.explain_run('avoid_obstacle.py', said, False, None, (), cut, 'move_turtlebot3') == [
        "avoid_obstacle.py does not start: line 5, `print('======`: `SyntaxError: unterminated string literal "
        "(detected at line 5)`. A string is cut at the end of the line (a paste keeps only what the slide's box "
        "shows): end it on the same line" + see % '2-a-string-cut-at-the-end-of-a-line']
    lost = write(tmp_path, 'trajectory.py', "#! /usr/bin/env python\nimport rospy\n   # Import\n"
                 "from geometry msgs.msg import Twist\n        rospy.init node('vel publisher')\n")
    said = python_said('trajectory.py', 4, 'from geometry msgs.msg import Twist', 'SyntaxError: invalid syntax')
    assert feedback.explain_run('trajectory.py', said, False, None, (), lost, 'move_turtlebot3') == [
        "trajectory.py does not start: line 4, `from geometry msgs.msg import Twist`: `SyntaxError: invalid syntax`. "
        "The paste lost the underscores, a space for each `_`: `geometry msgs` for `geometry_msgs`, `init node` for "
        "`init_node`, `'vel publisher'` for `'vel_publisher'`: put every underscore back" + see % '3-lost-underscores']
    blocks = write(tmp_path, 'trajectory.py', "def talker():\n        move = 1\n       while True:\n")
    said = python_said('trajectory.py', 3, 'while True:',
                       'IndentationError: unindent does not match any outer indentation level')
    assert feedback.explain_run('trajectory.py', said, False, None, (), blocks, 'move_turtlebot3') == [
        "trajectory.py does not start: line 3, `while True:`: `IndentationError: unindent does not match any outer "
        "indentation level`. The paste starts the lines of one block at different columns: indent 4 spaces per "
        "level, every line of a block at the same column" + see % '4-indentationerror']
    said = python_said('l.py', 5, 'print msg.ranges[0]',
                       "SyntaxError: Missing parentheses in call to 'print'. Did you mean print(...)?")
    assert feedback.explain_run('l.py', said, False, None, ['l.py line 5: A'], None, 'move_turtlebot3') == [
        'l.py does not start under Python 3: l.py line 5: A' + see % 'python-2-prints']


def test_a_callback_that_fails_at_every_scan_is_explained_by_the_paste(tmp_path):
    see = ' (see docs/copying-the-slides/move_turtlebot3.md#%s)'
    script = write(tmp_path, 'laser_data.py', "import rospy\ndef callback(msq):\n    print(msg.ranges[0])\n")
    failed = ('[ERROR] [1795518131.483246, 1.800000]: bad callback: <function callback at 0x7f5a87f304a0>\n'
              'Traceback (most recent call last):\n'
              '  File "/usr/lib/python3/dist-packages/rospy/topics.py", line 750, in _invoke_callback\n    cb(msg)\n'
              '  File "move_turtlebot3/scripts/laser_data.py", line 3, in callback\n    print(msg.ranges[0])\n'
              "NameError: name 'msg' is not defined. Did you mean: 'msq'?\n")
    assert feedback.explain_run('move_turtlebot3/scripts/laser_data.py', failed, True, True, (), script,
                                'move_turtlebot3') == [
        "move_turtlebot3/scripts/laser_data.py fails in its callback, line 3: `NameError: name 'msg' is not "
        "defined`, at every scan: the paste wrote `msq` for `msg` (`def callback(msq):`): write `msg` everywhere"
        + see % '5-msq-for-msg']
    early = write(tmp_path, 'avoid_obstacle.py', 'def callback(msg):\n    pub.publish(move)\n')
    assert feedback.explain_run('avoid_obstacle.py', failed.replace("'msg' is not defined. Did you mean: 'msq'?",
                                                                    "'pub' is not defined"), True, True, (), early,
                                'move_turtlebot3')[0].endswith(
        "make `pub` and `move` before the `rospy.Subscriber` line" + see % 'avoid_obstaclepy-the-publisher')
    refused = ('[FATAL] [1795518264.212487]: unable to register publication [/cmd vel] with master: ERROR: '
               'parameter [topic] contains illegal chars\n')
    assert feedback.explain_run('t.py', refused, False, None, (), None, 'move_turtlebot3') == [
        "t.py does not start a node: ROS refuses the name `/cmd vel` (`contains illegal chars`): a name in quotes "
        "lost its underscore in the paste (a space for each `_`): put every underscore back"
        + see % '3-lost-underscores']


def test_every_section_a_sentence_names_is_a_heading_of_its_page():
    sections = [feedback.COPYING_FOLDER + section for mistakes in feedback.COPYING_SECTIONS.values()
                for section in mistakes.values()] + list(feedback.DOCKER_SECTIONS.values())
    for section in sections:
        page, anchor = section.split('#')
        with open(os.path.join(ROOT, page)) as text:
            assert anchor in heading_anchors(text.read()), section
    # And the pages link to each other by anchors that exist.
    for name in sorted(os.listdir(os.path.join(ROOT, feedback.COPYING_FOLDER))):
        with open(os.path.join(ROOT, feedback.COPYING_FOLDER, name)) as text:
            page = text.read()
        for anchor in re.findall(r'\]\(#([^)]+)\)', page):
            assert anchor in heading_anchors(page), (name, anchor)


def test_windows_line_endings_of_a_shebang_without_env_or_command(tmp_path):
    direct = feedback.script_problems(write(tmp_path, 'a.py', '#!/usr/bin/python3\r\n'))
    assert direct == ["a.py has Windows line endings (CRLF): rosrun stops at its #! line with "
                      "`/usr/bin/python3^M: bad interpreter`; convert the file with `sed -i 's/\\r$//' a.py` "
                      "(see docs/student-docker.md#windows-line-endings)"]
    assert feedback.script_problems(write(tmp_path, 'b.py', '#!\r\n'))[0].startswith('b.py has Windows line endings')
