"""Slides + pages = full marks. A student pastes each lab's code from the seeds (slides/pasted/:
what a paste gives, damage included) or types it as printed (slides/), meets the errors
docs/copying-the-slides/ quotes (each quoted line must be on the page, exactly as this machine
prints it), applies only the edits the pages prescribe, and hands the package in:
`rosrun course_grader grade LAB PACKAGE --no-container` (what ./grade.sh runs after its set-up)
must give full marks, and so must the student's own check (`rosrun course_grader check LAB`).

The terminals are test_student_workspace's: nothing but HOME, a PATH whose first python has no
rospy, and the student's devel/setup.bash."""
import csv
import os
import re
import shutil

import pytest

from course_testing.processes import free_port, stop_process_group
from course_testing.waiting import wait_until
from test_student_workspace import COURSE_DEVEL, ROOT, SLIDES, new_student

PASTED = os.path.join(SLIDES, 'pasted')
PAGES = os.path.join(ROOT, 'docs', 'copying-the-slides')


def page(lab):
    with open(os.path.join(PAGES, lab + '.md')) as text:
        return text.read()


def slide(name, folder=SLIDES):
    with open(os.path.join(folder, name)) as text:
        return text.read()


def quoted(student, output, pattern, lab):
    """The first output line matching `pattern`, with the student's home written /home/you as the
    pages write it; it must be on the lab's copying page, exactly."""
    lines = [line.replace(student.home, '/home/you') for line in output.splitlines()
             if re.search(pattern, line)]
    assert lines, 'no line matching %r in:\n%s' % (pattern, output[-3000:])
    assert lines[0] in page(lab), '%s.md does not quote %r' % (lab, lines[0])
    return lines[0]


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


@pytest.fixture(scope='module')
def student():
    someone, _ = new_student()
    yield someone
    someone.stop_all()
    shutil.rmtree(someone.home)


def make_package(student, command, package):
    """catkin_create_pkg, then `rospack find` must name the student's own copy (the page's check)."""
    status, output = student.run('cd src && %s && rospack profile > /dev/null && rospack find %s' % (command, package))
    assert status == 0, output
    assert output.splitlines()[-1] == os.path.join(student.workspace, 'src', package), output


def grade(student, lab):
    """The teacher's grading of the student's package, on this machine: (score, max, the report's row)."""
    out = os.path.join(student.home, 'grades-' + lab)
    status, output = student.run('source %s/setup.bash && rosrun course_grader grade %s %s --no-container --out %s'
                                 % (COURSE_DEVEL, lab, os.path.join(student.workspace, 'src', lab), out),
                                 timeout=900, source=False)
    assert status == 0, output[-3000:]
    print(output[-600:])   # the grader's lines, for pytest -s
    with open(os.path.join(out, 'grades.csv')) as table:
        row = next(csv.DictReader(table))
    return int(float(row['score'])), int(float(row['max_score'])), row, output


def check(student, lab, *options):
    """The student's own check, in the student's terminal (the overlay's package, found by rospack):
    the package it names and the lines it ends with."""
    status, output = student.run('rosrun course_grader check %s %s' % (lab, ' '.join(options)), timeout=900)
    kept = re.search(r'^check: pictures and logs in (/\S+)$', output, re.M)
    if kept:   # a folder of the check's own in /tmp
        shutil.rmtree(os.path.dirname(kept.group(1)))
    assert status == 0, output[-3000:]
    print(output[-1500:])
    package = os.path.join(student.workspace, 'src', lab)
    assert 'check: grading the package at %s with the rubric of %s' % (package, lab) in output, output
    assert re.search(r'^check: built in [0-9.]+ s$', output, re.M), output   # each step with its time
    assert output.rstrip().endswith("check: This is your own check: the teacher's run, in a container, "
                                    "is the one that counts."), output[-500:]
    return output


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

    def rosrun(script):
        return student.run('DISPLAY= rosrun move_turtlebot3 %s' % script, timeout=60)[1]

    # As pasted: `#!` is not in column 1, so bash runs the file; `import` is ImageMagick's.
    paste('laser_data.py')
    output = rosrun('laser_data.py')
    quoted(student, output, r'unable to open X server', lab)
    quoted(student, output, r'line 3: from: command not found', lab)
    # `#!` in column 1: Python, which stops at the string cut at the end of line 6.
    paste('laser_data.py', column_one)
    output = rosrun('laser_data.py')
    quoted(student, output, r'laser_data\.py", line 6$', lab)
    quoted(student, output, r'^SyntaxError: unterminated string literal', lab)
    paste('laser_data.py', column_one, one_line_string)
    output = rosrun('laser_data.py')
    quoted(student, output, r'from sensor msgs', lab)
    paste('laser_data.py', column_one, one_line_string, underscores)
    output = rosrun('laser_data.py')   # the page's section on Python 2 prints
    quoted(student, output, r'laser_data\.py", line 9$', lab)
    quoted(student, output, r"^SyntaxError: Missing parentheses in call to 'print'", lab)
    paste('trajectory.py', underscores)
    output = rosrun('trajectory.py')
    quoted(student, output, r'trajectory\.py", line 14$', lab)
    quoted(student, output, r'^IndentationError: unindent does not match', lab)

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
    score, full, row, output = grade(student, lab)
    assert (score, full) == (14, 14), (row, output[-2000:])
    output = check(student, lab)
    assert re.search(r'^check: total 14 / 14 \(\d+ s\)$', output, re.M), output[-2000:]
    assert len(re.findall(r'^check: \S+ checked in [0-9.]+ s$', output, re.M)) == 3, output[-2000:]


def stage3_from_the_page():
    """The stage-3 file as docs/copying-the-slides/my_turtle.md prints it (before the lin_vel_ edit)."""
    text = page('my_turtle')
    block = text.split('<!-- stage 3, whole -->')[1].split('\n\n    #include')[1]
    code = '    #include' + block.split('\n\n*')[0]
    return '\n'.join(line[4:] for line in code.split('\n')) + '\n'


def test_my_turtle_slides_then_the_pages_edits_get_full_marks(student):
    lab = 'my_turtle'
    make_package(student, 'catkin_create_pkg my_turtle std_msgs rospy roscpp', lab)
    student.copy_slide('CMakeLists_my_turtle.txt', 'src/my_turtle/CMakeLists.txt')
    student.copy_slide('move_turtle.launch', 'src/my_turtle/launch/move_turtle.launch')
    # Stage 2's edits (CMakeLists.txt and package.xml find turtlesim and geometry_msgs).
    student.edit('src/my_turtle/CMakeLists.txt', '  std_msgs\n)', '  std_msgs\n  geometry_msgs\n  turtlesim\n)')
    student.edit('src/my_turtle/package.xml', '  <exec_depend>std_msgs</exec_depend>',
                 '  <exec_depend>std_msgs</exec_depend>\n  <depend>geometry_msgs</depend>\n'
                 '  <depend>turtlesim</depend>')
    # Stage 3 as the page puts it together: stage 2's pose subscriber kept.
    code = stage3_from_the_page()
    assert slide('my_turtle_node_stage2.cpp').split('int main')[0] in code
    assert 'node.subscribe("turtle1/pose", 10, poseCallback)' in code
    student.write('src/my_turtle/src/my_turtle_node.cpp', code)
    status, output = student.run('catkin_make')
    assert status != 0
    quoted(student, output, r'my_turtle_node\.cpp:13:5: error: .lin_vel_. was not declared', lab)
    quoted(student, output, r'my_turtle_node\.cpp:14:5: error: .ang_vel_. was not declared', lab)
    student.edit('src/my_turtle/src/my_turtle_node.cpp', 'void velocityCallback',
                 'double lin_vel_ = 0.0, ang_vel_ = 0.0;  // the last teleop command\n\nvoid velocityCallback')
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]
    score, full, row, output = grade(student, lab)
    assert (score, full) == (9, 9), (row, output[-2000:])
    output = check(student, lab)
    assert re.search(r'^check: total 9 / 9 \(\d+ s\)$', output, re.M), output[-2000:]
    assert re.findall(r'^(PASS|FAIL) (\S+)', output, re.M) == [
        ('PASS', 'builds'), ('PASS', 'launch'), ('PASS', 'teleop'), ('PASS', 'prints_pose')], output[-2000:]


def test_ros_exercises_fig5_pasted_then_the_pages_edits_get_full_marks(student):
    lab = 'ros_exercises'
    # The report prints only Fig. 5 as text: the other programs and the launch files are the
    # course's (the lab's README says what each must do; the page points there).
    make_package(student, 'catkin_create_pkg ros_exercises roscpp std_msgs geometry_msgs turtlesim', lab)
    package = os.path.join(student.workspace, 'src', lab)
    shutil.rmtree(package)
    shutil.copytree(os.path.join(ROOT, 'src', lab), package)
    circle = 'src/ros_exercises/src/circle.cpp'
    student.write(circle, slide('circle.cpp.txt', PASTED))
    status, output = student.run('catkin_make')
    assert status != 0
    for pattern in (r'circle\.cpp:3:10: error: #include expects', r'circle\.cpp:7:27: error: .turtlesim. does not name',
                    r'circle\.cpp:30:20: error: .geonetry_msgs. was not declared in this scope$',
                    r'circle\.cpp:34:6: error: .Spin. is not a member'):
        quoted(student, output, pattern, lab)
    # The include, with turtlesim's Pose.h below it: the errors the first build hid.
    student.edit(circle, '#include *geonetry_msgs/Twist.h"',
                 '#include "geometry_msgs/Twist.h"\n#include "turtlesim/Pose.h"')
    status, output = student.run('catkin_make')
    assert status != 0
    quoted(student, output, r'circle\.cpp:14:8: error: .*has no member named .ltnear.; did you mean .linear.\?', lab)
    quoted(student, output, r'circle\.cpp:31:20: error: .geonetry_msgs. was not declared in this scope; did you', lab)
    # The page's other edits: the names, the spin, ros::init, and the rubric's turtle, speeds and text.
    for old, new in (('my_vel.ltnear.x = 1.6;', 'my_vel.linear.x = 1.0;'),
                     ('my_vel.angular.z = 2.1;', 'my_vel.angular.z = 1.0;'),
                     ('subscriber@(%f', 'subscriber@[%f'),
                     ('geonetry_msgs::Twist>("robotics/cmd_vel"', 'geometry_msgs::Twist>("turtle1/cmd_vel"'),
                     ('"robotics/pose"', '"turtle1/pose"'), ('ros::Spin();', 'ros::spin();'),
                     ('ros::NodeHandle nh;', 'ros::init(argc, argv, "circle");\n\nros::NodeHandle nh;')):
        student.edit(circle, old, new)
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]
    score, full, row, output = grade(student, lab)
    assert (score, full) == (18, 18), (row, output[-2000:])
    # The one criterion the student's edits touched, as the lab's README suggests: one run, not six.
    output = check(student, lab, '--only', 'circle')
    assert re.findall(r'^(PASS|FAIL) (\S+)', output, re.M) == [('PASS', 'circle')], output[-2000:]
    assert re.findall(r'^check: \S+ checked in', output, re.M) == ['check: exercise3.launch checked in'], output
    assert re.search(r'^check: circle 2 / 2, the other criteria not checked \(\d+ s\)$', output, re.M), output
