"""Each lab is one table of runs (RUNS) beside its static criteria: the criteria its rubric is
checked against, what run_checks runs and the wall limit's steps all come from it."""
import copy
import types

import pytest
import yaml

from course_grader import labs, rubric as rubrics
from course_grader.wall_limit import NODES, READING


def decided_by(module):
    """{criterion id: the settings its check reads}, from the lab's table and static criteria."""
    return dict(module.STATIC_CRITERIA, **{criterion_id: settings for run in module.RUNS
                                           for criterion_id, settings in run.criteria.items()})


def by_id(criteria, criterion_id):
    return next(criterion for criterion in criteria if criterion['id'] == criterion_id)


def refusal(lab, shipped, change):
    """Why the lab's `shipped` rubric (its data), its criteria changed by change(list of mappings),
    does not fit the lab."""
    data = copy.deepcopy(shipped)
    change(data['criteria'])
    module = labs.lab_module(lab)
    with pytest.raises(rubrics.RubricError) as refused:
        rubrics.Rubric(data, 'x.yaml').check_against(module.CRITERIA, module.__name__)
    return str(refused.value)


def test_every_lab_has_a_rubric():
    assert rubrics.labs() == sorted(labs.LABS)


@pytest.mark.parametrize('lab', labs.LABS)
def test_each_criterion_is_decided_once_by_a_run_or_without_one(lab):
    module = labs.lab_module(lab)
    ids = list(module.STATIC_CRITERIA) + [criterion_id for run in module.RUNS for criterion_id in run.criteria]
    assert len(ids) == len(set(ids))
    assert module.CRITERIA == decided_by(module) and list(module.CRITERIA) == ids


@pytest.mark.parametrize('lab', labs.LABS)
def test_each_step_runs_a_script_or_a_launch_file_or_only_reads(lab):
    for run in labs.lab_module(lab).RUNS:
        # A launch file with one executable's node alone: FILE:EXECUTABLE.
        assert run.name.split(':')[0].endswith(('.py', '.launch')), run
        assert run.kinds and set(run.kinds) <= {NODES, READING}, run
        assert run.criteria or run.kinds == (READING,), run   # a step that decides nothing reads


@pytest.mark.parametrize('lab', labs.LABS)
def test_run_checks_runs_the_table(lab, monkeypatch):
    module = labs.lab_module(lab)
    handed = []
    monkeypatch.setattr(module, 'run_each', lambda session, runs, **given: handed.append(runs) or {})
    module.run_checks(types.SimpleNamespace(rubric=rubrics.load(lab), only=None))
    assert handed == [module.RUNS]


@pytest.mark.parametrize('lab', labs.LABS)
def test_static_checks_decide_the_static_criteria_but_the_build(lab):   # builds: the session's build
    module = labs.lab_module(lab)
    session = types.SimpleNamespace(rubric=rubrics.load(lab), script=lambda name: None)
    assert set(module.static_checks(session)) == set(module.STATIC_CRITERIA) - {'builds'}


def test_ros_exercises_reads_the_launch_file_of_each_run_at_once_first(monkeypatch):
    module = labs.lab_module('ros_exercises')
    rubric = rubrics.load('ros_exercises')
    read = []
    monkeypatch.setattr(module, 'describe_launches', lambda session, launches: read.append(launches))
    reading = module.RUNS[0]
    assert not reading.criteria and reading.check(types.SimpleNamespace(rubric=rubric)) == {}
    files = {run.name: rubric.criterion(next(iter(run.criteria)))['launch_file'] for run in module.RUNS[1:]}
    # The subscriber's run reads exercise1.launch with the publisher's arguments: the same reading.
    assert files.pop('exercise1.launch:subscriber') == files['exercise1.launch']
    assert [[launch_file for launch_file, _ in launches] for launches in read] == [list(files.values())]


@pytest.mark.parametrize('lab', labs.LABS)
def test_a_rubric_that_disagrees_with_its_labs_table_is_refused(lab):
    with open(rubrics.load(lab).path) as stream:
        shipped = yaml.safe_load(stream)
    assert 'criterion undecided is not one that' in refusal(
        lab, shipped, lambda criteria: criteria.append({'id': 'undecided', 'title': 't', 'points': 1}))
    for criterion_id, settings in decided_by(labs.lab_module(lab)).items():
        assert 'criterion %s of' % criterion_id in refusal(
            lab, shipped, lambda criteria: criteria.remove(by_id(criteria, criterion_id)))
        for setting in settings:
            assert 'criterion %s has no %s ' % (criterion_id, setting) in refusal(
                lab, shipped, lambda criteria: by_id(criteria, criterion_id).pop(setting))
