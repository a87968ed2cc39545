"""Rubric files (rubrics/<lab>.yaml): what is graded, for how many points, with which thresholds."""
import os

import rospkg
import yaml

from course_grader.labs import LABS, lab_module

LIMITS = ('build_seconds', 'run_seconds', 'start_seconds', 'stop_seconds')


def rubric_dir():
    """The package's rubrics/: in the source tree or in the install space, wherever it was found."""
    return os.path.join(rospkg.RosPack().get_path('course_grader'), 'rubrics')


class RubricError(Exception):
    """A rubric file a teacher edited cannot be used: the message says where and why."""


class Criterion:
    def __init__(self, entry, where):
        if not isinstance(entry, dict):
            raise RubricError('%s: each criterion is a mapping with id, title and points' % where)
        for key in ('id', 'title', 'points'):
            if key not in entry:
                raise RubricError('%s: a criterion has no %r' % (where, key))
        self.id = str(entry['id'])
        self.title = str(entry['title'])
        points = entry['points']
        if isinstance(points, bool) or not isinstance(points, (int, float)) or points < 0:
            raise RubricError('%s: points of %r must be a number >= 0, not %r' % (where, self.id, points))
        self.points = points
        self.settings = {k: v for k, v in entry.items() if k not in ('id', 'title', 'points')}

    def __getitem__(self, key):
        """A setting of the criterion (a threshold, a file name): the rubric's, there is no default."""
        return self.settings[key]


class Rubric:
    def __init__(self, data, path):
        if not isinstance(data, dict):
            raise RubricError('%s: the file must be a mapping (lab, package, criteria)' % path)
        for key in ('lab', 'package', 'criteria'):
            if key not in data:
                raise RubricError('%s: no %r' % (path, key))
        self.path = path
        self.lab = str(data['lab'])
        self.title = str(data.get('title', self.lab))
        self.package = str(data['package'])
        if not isinstance(data['criteria'], list) or not data['criteria']:
            raise RubricError('%s: criteria must be a non-empty list' % path)
        self.criteria = [Criterion(entry, '%s, criterion %d' % (path, number))
                         for number, entry in enumerate(data['criteria'], 1)]
        ids = [c.id for c in self.criteria]
        duplicates = sorted({i for i in ids if ids.count(i) > 1})
        if duplicates:
            raise RubricError('%s: criterion ids used twice: %s' % (path, ', '.join(duplicates)))
        self.limits = data.get('limits') or {}
        if not isinstance(self.limits, dict) or set(LIMITS) - set(self.limits):
            raise RubricError('%s: limits must give %s' % (path, ', '.join(LIMITS)))

    def check_against(self, known, lab_module):
        """Refuse, before anything runs, a criterion the lab does not check, a check of the lab the
        rubric forgets, a setting a check reads that the rubric does not give, and a setting the
        rubric gives that no check reads (a misspelt threshold would otherwise change nothing);
        `known` is the lab's CRITERIA: {criterion id: settings its check reads}."""
        ids = [c.id for c in self.criteria]
        unknown = [i for i in ids if i not in known]
        if unknown:
            raise RubricError('%s: criterion %s is not one that %s checks (it checks: %s)' % (
                self.path, ', '.join(unknown), lab_module, ', '.join(known)))
        forgotten = [i for i in known if i not in ids]
        if forgotten:
            raise RubricError('%s: criterion %s of %s is missing from the rubric (give it, with 0 points '
                              'to leave it out of the grade)' % (self.path, ', '.join(forgotten), lab_module))
        for criterion in self.criteria:
            missing = [key for key in known[criterion.id] if key not in criterion.settings]
            if missing:
                raise RubricError('%s: criterion %s has no %s (its check in %s reads them)' % (
                    self.path, criterion.id, ', '.join(missing), lab_module))
            unread = sorted(key for key in criterion.settings if key not in known[criterion.id])
            if unread:
                raise RubricError('%s: criterion %s gives %s, which its check in %s does not read (it reads: %s)' % (
                    self.path, criterion.id, ', '.join(unread), lab_module, ', '.join(known[criterion.id]) or 'none'))

    @property
    def max_score(self):
        return sum(c.points for c in self.criteria)

    def criterion(self, criterion_id):
        for criterion in self.criteria:
            if criterion.id == criterion_id:
                return criterion
        raise KeyError(criterion_id)


def labs():
    """The labs that have a rubric, sorted."""
    return sorted(name[:-5] for name in os.listdir(rubric_dir()) if name.endswith('.yaml'))


def load(lab_or_path):
    """The rubric of a lab (by name) or of a YAML file (by path), checked against the lab's checks."""
    path = lab_or_path if lab_or_path.endswith('.yaml') else os.path.join(rubric_dir(), lab_or_path + '.yaml')
    if not os.path.isfile(path):
        raise RubricError('no rubric for lab %r (the labs are: %s)' % (lab_or_path, ', '.join(labs())))
    try:
        with open(path) as stream:
            data = yaml.safe_load(stream)
    except yaml.YAMLError as error:
        raise RubricError('%s is not valid YAML: %s' % (path, error))
    rubric = Rubric(data, path)
    if rubric.lab not in LABS:
        raise RubricError('%s: lab %r is none of the grader\'s (%s)' % (path, rubric.lab, ', '.join(sorted(LABS))))
    lab = lab_module(rubric.lab)
    rubric.check_against(lab.CRITERIA, lab.__name__)
    return rubric
