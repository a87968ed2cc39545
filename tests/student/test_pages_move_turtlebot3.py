"""Slides + pages = full marks: the move_turtlebot3 lab (001, pasted from the seed),
graded by the teacher's command and checked by the student's own (slides_and_pages.py says how)."""
import os
import re

from course_common.processes import free_port, stop_process_group
from course_common.waiting import wait_until
from slides_and_pages import PASTED, full_marks_then_checked, make_package, quoted, slide


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

    def paste(script, *edits):
        text = slide(script + '.txt', PASTED)
        for edit in edits:
            text = edit(text)
        path = student.write(scripts + script, text)
        os.chmod(path, 0o755)

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
    ]
    for script, edits, patterns in steps:
        paste(script, *edits)
        output = student.run('DISPLAY= rosrun move_turtlebot3 %s' % script, timeout=60)[1]
        for pattern in patterns:
            quoted(student, output, pattern, lab)

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
