"""Slides + pages = full marks: the my_turtle lab (000, typed as printed),
graded by the teacher's command and checked by the student's own (slides_and_pages.py says how)."""
import re

from slides_and_pages import check_names_the_sections, full_marks_then_checked, make_package, page, quoted, slide

PAGE = 'docs/copying-the-slides/my_turtle.md#'


def stage3_from_the_page():
    """The stage-3 file as docs/copying-the-slides/my_turtle.md prints it (before the lin_vel_ edit)."""
    text = page('my_turtle')
    block = text.split('<!-- stage 3, whole -->')[1].split('\n\n    #include')[1]
    code = '    #include' + re.split(r'\n\n(?=\S)', block)[0]
    return '\n'.join(line[4:] for line in code.split('\n')) + '\n'


def test_my_turtle_slides_then_the_pages_edits_get_full_marks(student):
    lab = 'my_turtle'
    make_package(student, 'catkin_create_pkg my_turtle std_msgs rospy roscpp', lab)
    student.copy_slide('CMakeLists_my_turtle.txt', 'src/my_turtle/CMakeLists.txt')
    student.copy_slide('move_turtle.launch', 'src/my_turtle/launch/move_turtle.launch')
    # Stage 3 as the page puts it together: stage 2's pose subscriber kept.
    code = stage3_from_the_page()
    assert slide('my_turtle_node_stage2.cpp').split('int main')[0] in code
    assert 'node.subscribe("turtle1/pose", 10, poseCallback)' in code
    student.write('src/my_turtle/src/my_turtle_node.cpp', code)
    # Before stage 2's edits, the student's check names the page's section on turtlesim's header.
    check_names_the_sections(student, lab, {'builds': (PAGE + 'turtlesimposeh-no-such-file-or-directory', [
        ('my_turtle_node.cpp line 3: turtlesim/Pose.h: No such file or directory',
         'my_turtle_node.cpp:3:10: fatal error: turtlesim/Pose.h: No such file or directory'),
        'find_package(catkin REQUIRED COMPONENTS', '<depend>turtlesim</depend>'])}, built=False)
    # Stage 2's edits (CMakeLists.txt and package.xml find turtlesim and geometry_msgs).
    student.edit('src/my_turtle/CMakeLists.txt', '  std_msgs\n)', '  std_msgs\n  geometry_msgs\n  turtlesim\n)')
    student.edit('src/my_turtle/package.xml', '  <exec_depend>std_msgs</exec_depend>',
                 '  <exec_depend>std_msgs</exec_depend>\n  <depend>geometry_msgs</depend>\n'
                 '  <depend>turtlesim</depend>')
    status, output = student.run('catkin_make')
    assert status != 0
    quoted(student, output, r'my_turtle_node\.cpp:13:5: error: .lin_vel_. was not declared', lab)
    quoted(student, output, r'my_turtle_node\.cpp:14:5: error: .ang_vel_. was not declared', lab)
    check_names_the_sections(student, lab, {'builds': (PAGE + 'lin_vel_-was-not-declared', [
        ('my_turtle_node.cpp line 13: ', 'my_turtle_node.cpp:13:5: error: '), 'lin_vel_',
        'was not declared in this scope'])}, built=False)
    student.edit('src/my_turtle/src/my_turtle_node.cpp', 'void velocityCallback',
                 'double lin_vel_ = 0.0, ang_vel_ = 0.0;  // the last teleop command\n\nvoid velocityCallback')
    status, output = student.run('catkin_make')
    assert status == 0, output[-3000:]
    # The student's check on the relay, which the page's last edit made build.
    full_marks_then_checked(student, lab, 9, 'teleop')
