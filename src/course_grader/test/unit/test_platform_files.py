"""The files a teacher gives GitHub Classroom and Gradescope: the workflow of each lab, and the
autograder bundle."""
import os
import re
import stat
import subprocess
import zipfile

import pytest
import yaml

from course_grader import classroom, platform_files, rubric as rubrics, sandbox

ACTIONS = {'actions/checkout', 'classroom-resources/autograding-grading-reporter'}


def workflow(lab, tmp_path, image='registry.example.org/teacher/ros-course:bookworm'):
    folder = tmp_path / lab
    platform_files.write_classroom_template(rubrics.load(lab), str(folder), image)
    text = (folder / '.github' / 'workflows' / 'classroom.yml').read_text()
    return text, yaml.safe_load(text)


@pytest.mark.parametrize('lab', rubrics.labs())
def test_each_labs_workflow_uses_only_the_pinned_checkout_and_reporter(lab, tmp_path):
    text, data = workflow(lab, tmp_path)
    assert data['on'] == ['push', 'repository_dispatch', 'workflow_dispatch']
    assert data['permissions'] == {'checks': 'write', 'actions': 'read', 'contents': 'read'}
    (job,) = data['jobs'].values()
    uses = [step['uses'] for step in job['steps'] if 'uses' in step]
    assert {use.split('@')[0] for use in uses} == ACTIONS
    for use in uses:
        assert re.fullmatch(r'[\w-]+/[\w-]+@[0-9a-f]{40}', use), use   # a commit, not a movable tag
    assert job['env'] == {'COURSE_IMAGE': 'registry.example.org/teacher/ros-course:bookworm', 'COURSE_LAB': lab}
    assert not re.search(r'@[A-Z_]+@', text)   # no placeholder left


@pytest.mark.parametrize('lab', rubrics.labs())
def test_the_reporter_reads_one_runner_per_criterion_from_the_grading_step(lab, tmp_path):
    _, data = workflow(lab, tmp_path)
    (job,) = data['jobs'].values()
    grade = next(step for step in job['steps'] if step.get('id') == classroom.GRADE_STEP)
    reporter = job['steps'][-1]
    ids = [c.id for c in rubrics.load(lab).criteria]
    assert reporter['with']['runners'] == ','.join(ids)
    assert reporter['env'] == {classroom.env_name(i): '${{ steps.%s.outputs.%s }}' % (grade['id'], i) for i in ids}
    assert job['steps'].index(grade) == len(job['steps']) - 2


def grader_docker_run(monkeypatch, tmp_path):
    """The `docker run` command ./grade.sh starts for one student (caught, not run)."""
    caught = []

    def popen(command, **_):
        caught.append(command)
        raise RuntimeError('caught')
    monkeypatch.setattr(sandbox.subprocess, 'Popen', popen)
    monkeypatch.setattr(sandbox.subprocess, 'run', lambda *a, **k: None)
    grading = sandbox.Grading(rubrics.load('move_turtlebot3'), '/sub', 'pkg', 'alice', str(tmp_path))
    with pytest.raises(RuntimeError):
        sandbox.run(grading, sandbox.Options(image='IMAGE'))
    return caught[0]


def test_the_grading_step_starts_its_container_as_grade_sh_does(monkeypatch, tmp_path):
    command = grader_docker_run(monkeypatch, tmp_path)
    ours = platform_files.container_options()
    # ./grade.sh's options but its container's name and the mounts, in the same order.
    theirs = command[2:command.index('IMAGE')]
    name = theirs.index('--name')
    del theirs[name:name + 2]
    mount = theirs.index('/sub:/submission:ro')
    del theirs[mount - 1:mount + 1]
    assert ours == theirs
    text, _ = workflow('move_turtlebot3', tmp_path)
    for line in platform_files.option_lines(ours):
        assert '            %s \\\n' % line in text


def test_the_bundle_holds_setup_and_run_autograder_executable_at_its_root(tmp_path):
    path = platform_files.write_gradescope_bundle(rubrics.load('my_turtle'), str(tmp_path / 'my_turtle.zip'))
    with zipfile.ZipFile(path) as bundle:
        assert sorted(bundle.namelist()) == ['Dockerfile', 'run_autograder', 'setup.sh']
        modes = {info.filename: stat.S_IMODE(info.external_attr >> 16) for info in bundle.infolist()}
        assert modes == {'Dockerfile': 0o644, 'run_autograder': 0o755, 'setup.sh': 0o755}
        run = bundle.read('run_autograder').decode()
        dockerfile = bundle.read('Dockerfile').decode()
    assert 'grade_platform gradescope my_turtle /autograder/submission --results /autograder/results' in run
    assert 'FROM ${BASE}' in dockerfile and 'COPY --from=course / /srv/ros-course/' in dockerfile
    assert '@' not in dockerfile.replace('@LAB@', '')
    for name in ('run_autograder', 'setup.sh'):
        subprocess.run(['bash', '-n', os.path.join(platform_files.platforms_dir(), 'gradescope', name)], check=True)


def test_a_template_is_not_written_over_a_folder_with_files(tmp_path, capsys):
    (tmp_path / 'mine.txt').write_text('precious')
    assert platform_files.classroom_main(['my_turtle', str(tmp_path), '--image', 'x']) == 2
    assert 'is not empty: give a new folder' in capsys.readouterr().err
    assert os.listdir(str(tmp_path)) == ['mine.txt']
