"""Slides + pages = full marks: the ros_exercises lab (002, the report's Fig. 5 pasted),
graded by the teacher's command and checked by the student's own (slides_and_pages.py says how).

The package is the example class's model (the course's src/ros_exercises) with Fig. 5 pasted as
circle.cpp, which the page's edits make the same program as the model's: this grading is also the
model's in ./test.sh (grade_examples.test leaves the ros_exercises model out)."""
import os
import re
import shutil

from slides_and_pages import PASTED, check_names_the_sections, full_marks_then_checked, make_package, quoted, slide
from test_student_workspace import ROOT


def test_ros_exercises_fig5_pasted_then_the_pages_edits_get_full_marks(student):
    lab = 'ros_exercises'
    # The report prints only Fig. 5 as text: the other programs and the launch files are the
    # course's (the lab's README says what each must do; the page points there).
    make_package(student, 'catkin_create_pkg ros_exercises roscpp std_msgs geometry_msgs turtlesim', lab)
    package = os.path.join(student.workspace, 'src', lab)
    shutil.rmtree(package)
    shutil.copytree(os.path.join(ROOT, 'examples', 'grading', lab, 'model'), package)   # a link to src/ros_exercises
    circle = 'src/ros_exercises/src/circle.cpp'
    student.write(circle, slide('circle.cpp.txt', PASTED))
    status, output = student.run('catkin_make')
    assert status != 0
    for pattern in (r'circle\.cpp:3:10: error: #include expects', r'circle\.cpp:7:27: error: .turtlesim. does not name',
                    r'circle\.cpp:30:20: error: .geonetry_msgs. was not declared in this scope$',
                    r'circle\.cpp:34:6: error: .Spin. is not a member'):
        quoted(student, output, pattern, lab)
    # The student's check names the page's section, which quotes the error the check reports.
    check_names_the_sections(student, lab, {'builds': (
        'docs/copying-the-slides/ros_exercises.md#what-a-paste-of-fig-5-does-first', [
            ('circle.cpp line 3: #include expects "FILENAME" or <FILENAME>',
             'circle.cpp:3:10: error: #include expects "FILENAME" or <FILENAME>')])}, built=False)
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
    # The student's check on the one criterion the student's edits touched, as the lab's README
    # suggests: one run, not six.
    output = full_marks_then_checked(student, lab, 18, 'circle')
    assert re.findall(r'^check: \S+ checked in', output, re.M) == ['check: exercise3.launch checked in'], output
