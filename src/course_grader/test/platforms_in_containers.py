"""The platforms' side of the grading, run here as the platforms run it (GitHub and Gradescope
cannot be reached from CI): the Classroom workflow's `run:` steps in order, as a runner runs them
(bash -e, GITHUB_OUTPUT and GITHUB_WORKSPACE set, the checkout in submission/), its reporter's input
decoded as the reporter decodes it; and Gradescope's run_autograder in the image of the bundle's
Dockerfile (the course's root entered with chroot), a submission mounted at /autograder/submission. Scores
and sentences as examples/grading/<lab>/expected.yaml says ./grade.sh gives them.
Run by tools/platform-test.sh (CI, after tools/grade-test.sh), with COURSE_GRADER_IMAGE set."""
import base64
import io
import json
import os
import re
import shutil
import subprocess
import tarfile
import time
import zipfile

import pytest
import yaml

from course_grader import sandbox
from example_class import EXAMPLES, ROOT, expected, make_class

IMAGE = os.environ.get('COURSE_GRADER_IMAGE')
ENV_SH = os.path.join(ROOT, 'tools', 'env.sh')
# The examples each platform grades (the rest of each class is graded by tools/grade-test.sh).
# hostile: forks, fills its disk, spins, prints without end, writes outside, connects out;
# hostile_forger: a daemon that rewrites result.json; hostile_teleport: exercise 3's circle drawn
# with teleports. None may score more than expected.yaml says.
CLASSROOM = [('move_turtlebot3', 'model'), ('move_turtlebot3', 'slides_as_printed'), ('my_turtle', 'model'),
             ('ros_exercises', 'hostile_teleport'), ('move_turtlebot3', 'hostile'), ('move_turtlebot3', 'hostile_forger')]
GRADESCOPE = [('move_turtlebot3', 'no_chmod_early_stop'), ('my_turtle', 'forward_only')]
# Bad input, each one sentence (move_turtlebot3's repository): files, and that sentence.
MODEL_XML = '<package format="2"><name>move_turtlebot3</name></package>'
BAD_INPUTS = {
    'empty': ({}, 'the submission is empty: hand in the package move_turtlebot3 (the folder made by '
                  'catkin_create_pkg move_turtlebot3), at the top or in src/'),
    'no_package': ({'README.md': '# my lab\n'}, 'no package named move_turtlebot3 in the submission (a folder '
                   'with a package.xml saying <name>move_turtlebot3</name>); packages found: none'),
    'another_name': ({'my_turtle/package.xml': '<package><name>my_turtle</name></package>'},
                     'no package named move_turtlebot3 in the submission (a folder with a package.xml saying '
                     '<name>move_turtlebot3</name>); packages found: my_turtle (my_turtle)'),
    'two_copies': ({'move_turtlebot3/package.xml': MODEL_XML, 'src/move_turtlebot3/package.xml': MODEL_XML},
                   'the package move_turtlebot3 is there 2 times (move_turtlebot3, src/move_turtlebot3): hand in one'),
}

pytestmark = pytest.mark.skipif(not IMAGE, reason='run by tools/platform-test.sh, which makes the image')


def ros(command, **kwargs):
    """A command of the course's workspace on this machine (tools/env.sh sourced)."""
    return subprocess.run(['bash', '-c', 'source "$0" && exec "$@"', ENV_SH] + command, check=True,
                          stdout=subprocess.PIPE, universal_newlines=True, stdin=subprocess.DEVNULL, **kwargs).stdout


def student_folder(lab, student, tmp_path):
    return make_class(lab, str(tmp_path / 'class'))[student]


def bad_input(name, tmp_path):
    files, _ = BAD_INPUTS[name]
    folder = tmp_path / name
    folder.mkdir()
    for path, text in files.items():
        (folder / path).parent.mkdir(parents=True, exist_ok=True)
        (folder / path).write_text(text)
    return str(folder)


# GitHub Classroom


def read_github_output(path):
    """The step outputs a runner reads from $GITHUB_OUTPUT: name=value lines and name<<EOF blocks."""
    found, lines = {}, open(path).read().splitlines()
    while lines:
        line = lines.pop(0)
        if '<<' in line and ('=' not in line or line.index('<<') < line.index('=')):
            name, delimiter = line.split('<<', 1)
            value = []
            while lines[0] != delimiter:
                value.append(lines.pop(0))
            lines.pop(0)
            found[name] = '\n'.join(value)
        elif line:
            name, value = line.split('=', 1)
            found[name] = value
    return found


def expression(value, outputs):
    """A workflow expression of the kind the reporter's env uses: ${{ steps.ID.outputs.NAME }}."""
    def evaluate(match):
        step, name = match.group(1), match.group(2)
        return outputs.get(step, {}).get(name, '')
    return re.sub(r'\$\{\{\s*steps\.([\w-]+)\.outputs\.([\w-]+)\s*\}\}', evaluate, value)


def run_workflow(lab, submission, tmp_path):
    """The lab's workflow run as a runner runs it. Returns (the reporter's runners decoded, the log
    of each step by name, seconds of the steps)."""
    template = tmp_path / 'template'
    ros(['rosrun', 'course_grader', 'classroom_template', lab, str(template), '--image', IMAGE])
    workflow = yaml.safe_load((template / '.github' / 'workflows' / 'classroom.yml').read_text())
    (job,) = workflow['jobs'].values()
    workspace, temp = tmp_path / 'workspace', tmp_path / 'runner_temp'
    workspace.mkdir()
    temp.mkdir()
    env = dict(os.environ, CI='true', GITHUB_ACTIONS='true', GITHUB_WORKSPACE=str(workspace), RUNNER_TEMP=str(temp),
               **{key: str(value) for key, value in job['env'].items()})
    outputs, logs, runners = {}, {}, None
    started = time.monotonic()
    for step in job['steps']:
        uses = step.get('uses', '').split('@')[0]
        if uses == 'actions/checkout':
            # The student's repository, as the checkout leaves it (with its .git).
            target = workspace / step['with']['path']
            shutil.copytree(submission, str(target), symlinks=True)
            (target / '.git').mkdir(exist_ok=True)
        elif uses == 'classroom-resources/autograding-grading-reporter':
            # As the reporter reads its runners: <RUNNER>_RESULTS, base64-encoded JSON.
            variables = {name: expression(value, outputs) for name, value in step['env'].items()}
            runners = {runner: json.loads(base64.b64decode(variables['%s_RESULTS' % runner.strip().upper()]))
                       for runner in step['with']['runners'].split(',')}
        else:
            output = temp / ('output-%d' % len(logs))
            output.write_text('')
            script = temp / ('step-%d.sh' % len(logs))
            script.write_text(step['run'])
            run = subprocess.run(['bash', '-e', str(script)], cwd=str(workspace),
                                 env=dict(env, GITHUB_OUTPUT=str(output)), stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, universal_newlines=True, stdin=subprocess.DEVNULL)
            logs[step['name']] = run.stdout
            print('--- step %s (exit %d)\n%s' % (step['name'], run.returncode, run.stdout))
            assert run.returncode == 0, step['name']
            if 'id' in step:
                outputs[step['id']] = read_github_output(str(output))
    return runners, logs, time.monotonic() - started


def reporter_points(runners):
    """The points Classroom gets: the tests' scores and the max_scores, added up."""
    return (sum(t['score'] for data in runners.values() if data.get('max_score') for t in data['tests']),
            sum(data['max_score'] for data in runners.values() if data.get('max_score')))


@pytest.mark.parametrize('lab, student', CLASSROOM)
def test_classroom_workflow_grades_a_push_as_grade_sh(lab, student, tmp_path):
    runners, logs, seconds = run_workflow(lab, student_folder(lab, student, tmp_path), tmp_path)
    wanted = expected(lab)[student]
    print('classroom: %s %s: %s points in %.0f s; %s' % (lab, student, reporter_points(runners), seconds, [
        (runner, data['status'], data['tests'][0]['score'], data['max_score']) for runner, data in runners.items()]))
    assert reporter_points(runners)[0] == wanted['score']
    rubric = yaml.safe_load(open(os.path.join(ROOT, 'src', 'course_grader', 'rubrics', lab + '.yaml')))
    assert list(runners) == [c['id'] for c in rubric['criteria']]
    assert reporter_points(runners)[1] == sum(c['points'] for c in rubric['criteria'])
    for criterion in rubric['criteria']:
        data = runners[criterion['id']]
        assert data['max_score'] == criterion['points']
        assert data['status'] == ('pass' if data['tests'][0]['score'] == criterion['points'] else 'fail')
    # The reasons: in the reporter's input, and in the log of the step the student opens.
    for criterion_id, sentence in (wanted.get('sentences') or {}).items():
        assert sentence in runners[criterion_id]['tests'][0]['message']
        assert sentence in logs['Grade']
    assert 'total %g / %g' % reporter_points(runners) in logs['Grade']
    for parent, _, names in os.walk(str(tmp_path / 'workspace')):   # the checkout is mounted read-only
        assert 'hostile_was_here' not in names, parent


@pytest.mark.parametrize('name', sorted(BAD_INPUTS))
def test_classroom_bad_push_is_one_sentence_the_reporter_shows(name, tmp_path):
    runners, logs, _ = run_workflow('move_turtlebot3', bad_input(name, tmp_path), tmp_path)
    sentence = BAD_INPUTS[name][1]
    assert reporter_points(runners) == (0, 14)
    for data in runners.values():
        # The reporter prints an error's message and fails the run ("Some tests errored.").
        assert data['status'] == 'error' and data['tests'][0]['message'] == sentence
    assert 'not fully graded: %s' % sentence in logs['Grade']


def test_classroom_without_the_image_stops_at_the_image_step_saying_why(tmp_path):
    template = tmp_path / 'template'
    ros(['rosrun', 'course_grader', 'classroom_template', 'my_turtle', str(template),
         '--image', 'localhost:1/no-such-course-image:bookworm'])
    workflow = yaml.safe_load((template / '.github' / 'workflows' / 'classroom.yml').read_text())
    (job,) = workflow['jobs'].values()
    step = next(s for s in job['steps'] if s['name'] == 'Course image')
    run = subprocess.run(['bash', '-e', '-c', step['run']], env=dict(os.environ, **job['env']), stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, universal_newlines=True, stdin=subprocess.DEVNULL)
    assert run.returncode == 1
    assert ('::error::the course image localhost:1/no-such-course-image:bookworm cannot be pulled: the teacher '
            'pushes it once (docs/grading.md, GitHub Classroom); nothing was graded') in run.stdout


# Gradescope


@pytest.fixture(scope='module')
def gradescope_images(tmp_path_factory):
    """{lab: image}: the image of the bundle's Dockerfile, as a teacher builds it for Gradescope's
    manual Docker set-up, over a stand-in for Gradescope's base (debian:bookworm: Gradescope's
    own cannot be pulled here; run_autograder needs of it only bash, cp and chroot)."""
    made = {}
    for lab in sorted({lab for lab, _ in GRADESCOPE}):
        context = tmp_path_factory.mktemp('gradescope-' + lab)
        bundle = str(context / 'bundle.zip')
        ros(['rosrun', 'course_grader', 'gradescope_bundle', lab, bundle])
        with zipfile.ZipFile(bundle) as archive:
            for info in archive.infolist():   # zipfile drops the modes: as unzip, keep them
                archive.extract(info, str(context / 'source'))
                os.chmod(str(context / 'source' / info.filename), info.external_attr >> 16 & 0o777)
        made[lab] = subprocess.run(
            ['docker', 'build', '-q', '--network', 'none', '--build-arg', 'COURSE_IMAGE=' + IMAGE,
             '--build-arg', 'BASE=debian:bookworm', '-f', str(context / 'source' / 'Dockerfile'), str(context)],
            check=True, stdout=subprocess.PIPE, universal_newlines=True).stdout.strip()
    yield made
    for image in made.values():
        subprocess.run(['docker', 'rmi', image], stdout=subprocess.DEVNULL)


def run_autograder(image, submission, tmp_path, before=''):
    """run_autograder as Gradescope starts it (root, the submission at /autograder/submission),
    after the shell command `before` when given. Returns (results.json, what it printed, seconds)."""
    results = tmp_path / 'results'
    results.mkdir()
    started = time.monotonic()
    # Root, as Gradescope's harness; the memory and CPU docs/grading.md asks for, and a process limit
    # (Gradescope's own is not known; this machine is shared).
    run = subprocess.run(['docker', 'run', '--rm', '--network', 'none', '--user', 'root', '--memory', sandbox.MEMORY,
                          '--cpus', str(sandbox.CPUS), '--pids-limit', str(sandbox.PROCESSES),
                          '-v', '%s:/autograder/submission:ro' % submission, '-v', '%s:/autograder/results' % results,
                          image, 'bash', '-c', before + 'exec /autograder/run_autograder'], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT,
                         universal_newlines=True, stdin=subprocess.DEVNULL)
    seconds = time.monotonic() - started
    print(run.stdout)
    assert run.returncode == 0
    return json.loads((results / 'results.json').read_text(encoding='utf-8')), run.stdout, seconds


@pytest.mark.parametrize('lab, student', GRADESCOPE)
def test_gradescope_run_autograder_grades_the_submission_as_grade_sh(lab, student, gradescope_images, tmp_path):
    data, printed, seconds = run_autograder(gradescope_images[lab], student_folder(lab, student, tmp_path), tmp_path)
    wanted = expected(lab)[student]
    print('gradescope: %s %s: %s in %.0f s; %s' % (lab, student, data['score'], seconds, [
        (t['name'].rsplit('(', 1)[1][:-1], t['score'], t['max_score'], t['status']) for t in data['tests']]))
    assert data['score'] == wanted['score']
    assert {'score', 'execution_time', 'output', 'output_format', 'visibility', 'tests'} <= set(data)
    rubric = yaml.safe_load(open(os.path.join(ROOT, 'src', 'course_grader', 'rubrics', lab + '.yaml')))
    assert [t['name'] for t in data['tests']] == ['%s (%s)' % (c['title'], c['id']) for c in rubric['criteria']]
    assert sum(t['score'] for t in data['tests']) == data['score']
    assert sum(t['max_score'] for t in data['tests']) == sum(c['points'] for c in rubric['criteria'])
    for test in data['tests']:
        assert test['status'] == ('passed' if test['score'] == test['max_score'] else 'failed')
    for criterion_id, sentence in (wanted.get('sentences') or {}).items():
        test = next(t for t in data['tests'] if t['name'].endswith('(%s)' % criterion_id))
        assert sentence in test['output']
    assert 'total %g / %g' % (data['score'], sum(c['points'] for c in rubric['criteria'])) in printed


@pytest.mark.parametrize('name', ['empty', 'two_copies'])
def test_gradescope_bad_submission_is_one_sentence_in_results(name, gradescope_images, tmp_path):
    data, _, _ = run_autograder(gradescope_images['move_turtlebot3'], bad_input(name, tmp_path), tmp_path)
    assert data['score'] == 0
    assert 'not fully graded: %s' % BAD_INPUTS[name][1] in data['output']
    assert {t['output'] for t in data['tests']} == {BAD_INPUTS[name][1]}


# An upload of one archive and, beside it, results.json of full marks. The archive's links, each
# inside the archive's folder by its name, lead out of it when unpacked one through the other: in
# the chroot, a/p is the unpacking's parent folder (/tmp), p/r the chroot's root, so that the last
# lands at the chroot's /autograder/results/results.json, a link that the chroot's side follows to
# its copy of the upload but run_autograder's outer side to Gradescope's own upload, the forgery.
FORGED_LINK = ('autograder/results/results.json', '../../../../autograder/submission/forged.json')
PLANTING_LINKS = [('a', '.'), ('a/p', '..'), ('p/r', '..'), ('p/r/' + FORGED_LINK[0], FORGED_LINK[1])]
# The same link put in the chroot before the grading, as any other door of the chroot would leave it.
PLANTED_IN_THE_CHROOT = 'mkdir -p /srv/ros-course/autograder/results && ln -s %s /srv/ros-course/%s && ' % (
    FORGED_LINK[1], FORGED_LINK[0])
FULL_MARKS = {'score': 14, 'output': 'forged', 'tests': [{'name': 'all', 'score': 14, 'max_score': 14}]}


def new_folder(path):
    path.mkdir()
    return path


def upload(package_folder, folder, links=()):
    """`folder` as Gradescope keeps an upload: submission.tar.gz of what `package_folder` holds (and
    `links`, symbolic, after it), and forged.json beside it."""
    os.makedirs(folder)
    with tarfile.open(os.path.join(folder, 'submission.tar.gz'), 'w:gz') as archive:
        for name in sorted(os.listdir(package_folder)):
            archive.add(os.path.join(package_folder, name), arcname=name)
        for name, target in links:
            member = tarfile.TarInfo(name)
            member.type, member.linkname = tarfile.SYMTYPE, target
            archive.addfile(member, io.BytesIO())
    with open(os.path.join(folder, 'forged.json'), 'w') as stream:
        json.dump(FULL_MARKS, stream)
    return folder


@pytest.mark.parametrize('planted_by', ['archive', 'chroot'])
def test_gradescope_reads_no_link_planted_at_the_chroots_results(planted_by, gradescope_images, tmp_path):
    package = student_folder('move_turtlebot3', 'cmake_error', tmp_path)
    image = gradescope_images['move_turtlebot3']
    twin, _, _ = run_autograder(image, upload(package, str(tmp_path / 'twin')), new_folder(tmp_path / 'twin_run'))
    if planted_by == 'archive':
        hostile, printed, _ = run_autograder(image, upload(package, str(tmp_path / 'hostile'), PLANTING_LINKS),
                                             new_folder(tmp_path / 'hostile_run'))
    else:
        hostile, printed, _ = run_autograder(image, upload(package, str(tmp_path / 'hostile')),
                                             new_folder(tmp_path / 'hostile_run'), before=PLANTED_IN_THE_CHROOT)
    print('gradescope: planted by the %s: twin %s, hostile %s' % (planted_by, twin['score'], hostile['score']))
    assert twin['score'] == expected('move_turtlebot3')['cmake_error']['score']
    assert hostile['score'] <= twin['score']
    assert 'total %g / 14' % hostile['score'] in printed   # results.json is the grading's own


# The build starts it, in a session of its own: it finds the grading's ROS master among the
# loopback's ports and, whenever trajectory.py's node is up, drives the robot in the circle that
# node should have driven. Stopped after the build, it changes nothing.
CIRCLE_DAEMON = """
import os, socket, time, xmlrpc.client
socket.setdefaulttimeout(1)
def find_master():
    for port in range(1024, 65536):
        with socket.socket() as probe:
            if probe.connect_ex(('127.0.0.1', port)):
                continue
        try:
            if xmlrpc.client.ServerProxy('http://127.0.0.1:%d' % port).getSystemState('/d')[0] == 1:
                return 'http://127.0.0.1:%d' % port
        except Exception:
            pass
uri = find_master()
while not uri:
    time.sleep(0.5)
    uri = find_master()
os.environ['ROS_MASTER_URI'] = uri
import rospy
from geometry_msgs.msg import Twist
rospy.init_node('circle_daemon', disable_signals=True)
cmd_vel = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
move = Twist()
move.linear.x, move.angular.z = 1.0, 1.0
master = xmlrpc.client.ServerProxy(uri)
while True:
    if master.lookupNode('/d', '/vel_publisher')[0] == 1:
        cmd_vel.publish(move)
    time.sleep(0.1)
"""
# trajectory.py of both: a node that publishes nothing.
SILENT_TRAJECTORY = "#!/usr/bin/env python3\nimport rospy\nrospy.init_node('vel_publisher')\nrospy.spin()\n"


def silent_trajectory_with_daemon(folder):
    """The model with SILENT_TRAJECTORY, in `folder`, its build starting CIRCLE_DAEMON."""
    package = os.path.join(folder, 'move_turtlebot3')
    shutil.copytree(os.path.realpath(os.path.join(EXAMPLES, 'move_turtlebot3', 'model')), package)
    with open(os.path.join(package, 'scripts', 'trajectory.py'), 'w') as stream:
        stream.write(SILENT_TRAJECTORY)
    with open(os.path.join(package, 'circle_daemon.py'), 'w') as stream:
        stream.write(CIRCLE_DAEMON)
    with open(os.path.join(package, 'CMakeLists.txt'), 'a') as stream:
        stream.write('execute_process(COMMAND sh -c "setsid -f /usr/bin/python3 ${PROJECT_SOURCE_DIR}/circle_daemon.py '
                     '</dev/null >/dev/null 2>&1")\n')
    return folder


def test_gradescope_stops_a_daemon_of_the_build_before_the_runs(gradescope_images, tmp_path):
    """The model with a trajectory.py that publishes nothing, whose build leaves a daemon that
    drives the circle: the trajectory's criteria get nothing, every other criterion its full points
    as the model does (expected.yaml's model has them all). A daemon left running would draw the
    circle, or disturb the other runs."""
    hostile, printed, _ = run_autograder(gradescope_images['move_turtlebot3'],
                                         silent_trajectory_with_daemon(str(tmp_path / 'hostile')), new_folder(tmp_path / 'run'))
    scores = {t['name'].rsplit('(', 1)[1][:-1]: (t['score'], t['max_score']) for t in hostile['tests']}
    print('gradescope: %s' % scores)
    assert expected('move_turtlebot3')['model']['score'] == sum(most for _, most in scores.values())
    assert scores == {criterion: (0 if criterion in ('trajectory_rate', 'trajectory_circle') else most, most)
                      for criterion, (_, most) in scores.items()}
    assert 'cannot be stopped' not in printed
