"""Slides + pages = full marks: the move_turtlebot3 lab (001, pasted from the seed),
graded by the teacher's command and checked by the student's own (slides_and_pages.py says how)."""
import os
import re

from course_common.processes import free_port, stop_process_group
from course_common.waiting import wait_until
from slides_and_pages import PASTED, check_names_the_sections, full_marks_then_checked, make_package, quoted, slide

PAGE = 'docs/copying-the-slides/move_turtlebot3.md#'


# The edits of docs/copying-the-slides/move_turtlebot3.md, "What a paste does", as text edits.

def column_one(text):
    """`#!` in column 1: the indentation the whole paste arrived with (that of line 1) taken off."""
    lines = text.split('\n')
    common = len(lines[0]) - len(lines[0].lstrip(' '))
    return '\n'.join(line[common:] if not line[:common].strip() else line.lstrip(' ') for line in lines)


def four_spaces(text):
    """Each block 4 spaces further in than the line that opens it (def, if, else, while, try,
    except), as the page's rule says; comment lines are left as they are (Python ignores them)."""
    out, openers = [], []          # the pasted indentation of the lines that opened the open blocks
    for line in text.split('\n'):
        code = line.lstrip(' ')
        if not code or code.startswith('#'):
            out.append(line)
            continue
        pasted = len(line) - len(code)
        while openers and pasted <= openers[-1]:
            openers.pop()
        out.append('    ' * len(openers) + code)
        if code.split('#')[0].rstrip().endswith(':'):
            openers.append(pasted)
    return '\n'.join(out)


UNDERSCORES = [('sensor msgs', 'sensor_msgs'), ('geometry msgs', 'geometry_msgs'), ('init node', 'init_node'),
               ('is shutdown', 'is_shutdown'), ('queue size', 'queue_size'), ("'cmd vel'", "'cmd_vel'"),
               ("'vel publisher'", "'vel_publisher'"), ("'obstacle avoidance'", "'obstacle_avoidance'"),
               ("if name == ' main ':", "if __name__ == '__main__':")]


def underscores(text):
    for pasted, meant in UNDERSCORES:
        text = text.replace(pasted, meant)
    return text


def one_line_string(text):
    return re.sub(r"print\('=+\n", "print('==========')\n", text)


def print_function(text):
    return re.sub(r'print (ms[gq]\.ranges\[\d+\])', r'print(\1)', text)


def msg_not_msq(text):
    return text.replace('msq', 'msg')


def python3_line(text):
    return text.replace('#! /usr/bin/env python\n', '#!/usr/bin/env python3\n', 1)


def publisher_first(text):
    """avoid_obstacle.py: the queue_size, and the publisher and `move` made before the subscriber."""
    text = text.replace("pub = rospy.Publisher('/cmd_vel', Twist)",
                        "pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)")
    subscriber = "sub = rospy.Subscriber('/scan', LaserScan, callback)\n"
    start = text.index(subscriber)
    end = text.index('move = Twist()\n') + len('move = Twist()\n')
    return text[:start] + text[start + len(subscriber):end] + subscriber + text[end:]


def test_move_turtlebot3_pasted_then_the_pages_edits_get_full_marks(student):
    lab = 'move_turtlebot3'
    make_package(student, 'catkin_create_pkg move_turtlebot3 rospy geometry_msgs sensor_msgs', lab)
    scripts = 'src/move_turtlebot3/scripts/'

    def paste(script, *edits, mode=0o755):
        text = slide(script + '.txt', PASTED)
        for edit in edits:
            text = edit(text)
        path = student.write(scripts + script, text)
        os.chmod(path, mode)

    # The student's check of the three as pasted: each failure with the page's section for it, the
    # section quoting the line and error the check reports.
    for script in ('trajectory.py', 'laser_data.py', 'avoid_obstacle.py'):
        paste(script)
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]
    check_names_the_sections(student, lab, {
        'executable': (PAGE + 'python3-not-python-in-the-first-line', [
            '`#! /usr/bin/env python`', ("the lab's rubric gives this point only to a #! line that names `python3`",
                                         'the grader gives the `executable` point only to a `#!` line that names '
                                         'Python 3')]),
        'trajectory_rate': (PAGE + '3-lost-underscores', ['line 4', 'from geometry msgs.msg import Twist',
                                                          'SyntaxError: invalid syntax']),
        'laser_data': (PAGE + '1-the-whole-paste-indented', ['line 2', 'IndentationError: unexpected indent',
                                                             'unable to open X server', 'from: command not found']),
        'avoid_stops': (PAGE + '2-a-string-cut-at-the-end-of-a-line', [
            'line 8', "print('======", 'SyntaxError: unterminated string literal']),
    })

    # Each step of the page's section on copying: (script, the edits made so far, what the run prints
    # that the page quotes).
    steps = [
        # As pasted: `#!` is not in column 1, so bash runs the file; `import` is ImageMagick's.
        ('laser_data.py', (), [r'unable to open X server', r'line 3: from: command not found']),
        # `#!` in column 1: Python, which stops at the string cut at the end of line 6.
        ('laser_data.py', (column_one,),
         [r'laser_data\.py", line 6$', r'^SyntaxError: unterminated string literal']),
        ('laser_data.py', (column_one, one_line_string), [r'from sensor msgs']),
        # The page's section on Python 2 prints.
        ('laser_data.py', (column_one, one_line_string, underscores),
         [r'laser_data\.py", line 9$', r"^SyntaxError: Missing parentheses in call to 'print'"]),
        ('trajectory.py', (underscores,),
         [r'trajectory\.py", line 14$', r'^IndentationError: unindent does not match']),
        # Its prints fixed, avoid_obstacle.py stops at a line one space further in than the one above.
        ('avoid_obstacle.py', (one_line_string, underscores, print_function),
         [r'avoid_obstacle\.py", line 23$', r'^IndentationError: unexpected indent']),
    ]
    for script, edits, patterns in steps:
        paste(script, *edits)
        output = student.run('DISPLAY= rosrun move_turtlebot3 %s' % script, timeout=60)[1]
        for pattern in patterns:
            quoted(student, output, pattern, lab)

    # The student's check of these: the same errors, the same sections; and the same file saved
    # with Windows line endings (as an editor on Windows may) is named as such.
    paste('trajectory.py', underscores, python3_line, lambda text: text.replace('\n', '\r\n'))
    check_names_the_sections(student, lab, {
        'executable': ('docs/student-docker.md#windows-line-endings', [
            "env: 'python3\\r': No such file or directory", "sed -i 's/\\r$//'"]),
        'trajectory_rate': (PAGE + '4-indentationerror', [
            'line 14', 'IndentationError: unindent does not match any outer indentation level']),
        'laser_data': (PAGE + 'python-2-prints', ['line 9', 'print msg.ranges[0]']),
        'avoid_stops': (PAGE + '4-indentationerror', ['line 23', 'IndentationError: unexpected indent']),
    })

    # All edits but `msq`: the callback fails at every scan, against the simulator.
    paste('laser_data.py', column_one, one_line_string, underscores, four_spaces, print_function)
    port = free_port()
    master = 'export ROS_MASTER_URI=http://localhost:%d; ' % port
    world = student.start(master + 'exec roslaunch -p %d turtlebot3_gazebo turtlebot3_world.launch' % port, 'world')
    laser = student.start(master + 'exec rosrun move_turtlebot3 laser_data.py', 'laser_data')
    wait_until(lambda: 'NameError' in student.output(laser), 120, 'laser_data.py to fail in its callback')
    quoted(student, student.output(laser), r'^NameError: name .msg. is not defined', lab)
    for process in (laser, world):
        stop_process_group(process)
    # The student's check of it, and of avoid_obstacle.py with the same `msq`; trajectory.py done but
    # its execute bit (as a copy through a Windows folder leaves it).
    but_msq = (column_one, one_line_string, underscores, four_spaces, print_function)
    paste('avoid_obstacle.py', *but_msq, publisher_first)
    paste('trajectory.py', *but_msq, msg_not_msq, mode=0o644)
    check_names_the_sections(student, lab, {
        'executable': (PAGE + 'chmod-x', [('trajectory.py is not executable: run `chmod +x', 'chmod +x'),
                                          ('docs/student-docker.md#lost-executable-bits', 'student-docker.md')]),
        'laser_data': (PAGE + '5-msq-for-msg', ["NameError: name 'msg' is not defined", 'line 9']),
        'avoid_stops': (PAGE + '5-msq-for-msg', ["NameError: name 'msg' is not defined", 'def callback(msq):']),
    })

    # Every edit the page prescribes, then the teacher's grading.
    done = (column_one, one_line_string, underscores, four_spaces, print_function, msg_not_msq, python3_line)
    paste('trajectory.py', *done)
    paste('laser_data.py', *done)
    paste('avoid_obstacle.py', *done, publisher_first)
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]
    # The student's check on the criterion of the page's last edit.
    output = full_marks_then_checked(student, lab, 14, 'avoid_stops')
    assert re.findall(r'^check: \S+ checked in', output, re.M) == ['check: avoid_obstacle.py checked in'], output
