"""The files a teacher gives a platform for a lab (`rosrun course_grader classroom_template --help`,
`rosrun course_grader gradescope_bundle --help`): GitHub Classroom's template repository, whose
workflow grades each push in the course's image, and Gradescope's autograder bundle. Both run
`grade_platform` in the course's image (platform_grading.py)."""
import argparse
import os
import shlex
import sys
import zipfile

import rospkg

from course_grader import classroom, rubric as rubrics
from course_grader.sandbox import container_options


def option_lines(options):
    """The options grouped one flag (with its value) a line, shell-quoted."""
    lines = []
    for word in options:
        if word.startswith('-') or not lines:
            lines.append(shlex.quote(word))
        else:
            lines[-1] += ' ' + shlex.quote(word)
    return lines


def platforms_dir():
    return os.path.join(rospkg.RosPack().get_path('course_grader'), 'platforms')


def template(name):
    with open(os.path.join(platforms_dir(), name), encoding='utf-8') as stream:
        return stream.read()


def fill(text, rubric):
    return text.replace('@LAB@', rubric.lab).replace('@PACKAGE@', rubric.package)


def write_classroom_template(rubric, folder, image):
    """The template repository of the lab's assignment in `folder` (new or empty): the workflow,
    a README for the student and a .gitignore. Returns the paths written."""
    if os.path.exists(folder) and os.listdir(folder):
        raise OSError('%s is not empty: give a new folder' % folder)
    files = {os.path.join('.github', 'workflows', 'classroom.yml'):
             classroom.workflow(template('classroom.yml.in'), rubric, image, option_lines(container_options())),
             'README.md': fill(template('classroom-README.md.in'), rubric),
             '.gitignore': template('classroom.gitignore')}
    written = []
    for name, text in files.items():
        path = os.path.join(folder, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w', encoding='utf-8') as stream:
            stream.write(text)
        written.append(path)
    return written


def write_gradescope_bundle(rubric, path):
    """The autograder zip of the lab: setup.sh and run_autograder at its root (executable), and
    the Dockerfile of the image for Gradescope's manual Docker set-up."""
    with zipfile.ZipFile(path, 'w', zipfile.ZIP_DEFLATED) as bundle:
        for name in ('setup.sh', 'run_autograder', 'Dockerfile'):
            source = os.path.join(platforms_dir(), 'gradescope', name)
            info = zipfile.ZipInfo(name)
            info.external_attr = (0o100000 | (0o755 if os.access(source, os.X_OK) else 0o644)) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            bundle.writestr(info, fill(template(os.path.join('gradescope', name)), rubric))
    return path


def classroom_main(argv=None):
    parser = argparse.ArgumentParser(
        prog='rosrun course_grader classroom_template',
        description='Writes the template repository of a lab\'s GitHub Classroom assignment into FOLDER: '
                    '.github/workflows/classroom.yml (each push graded in the course\'s image, the points '
                    'reported to Classroom), README.md for the student, .gitignore. See docs/grading.md.')
    parser.add_argument('lab', help='the lab: %s' % ', '.join(rubrics.labs()))
    parser.add_argument('folder', help='a new folder')
    parser.add_argument('--image', required=True,
                        help='the course\'s image as the runners pull it, e.g. REGISTRY/OWNER/ros-course-grader:bookworm')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        written = write_classroom_template(rubrics.load(args.lab), args.folder, args.image)
    except (rubrics.RubricError, OSError) as error:
        print('classroom_template: %s' % error, file=sys.stderr)
        return 2
    print('\n'.join(written))
    return 0


def gradescope_main(argv=None):
    parser = argparse.ArgumentParser(
        prog='rosrun course_grader gradescope_bundle',
        description='Writes the Gradescope autograder of a lab (setup.sh and run_autograder in a zip) to '
                    'ZIP. It runs in the course\'s image: see docs/grading.md.')
    parser.add_argument('lab', help='the lab: %s' % ', '.join(rubrics.labs()))
    parser.add_argument('zip', help='the file to write, e.g. my_turtle-autograder.zip')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        print(write_gradescope_bundle(rubrics.load(args.lab), args.zip))
    except (rubrics.RubricError, OSError) as error:
        print('gradescope_bundle: %s' % error, file=sys.stderr)
        return 2
    return 0
