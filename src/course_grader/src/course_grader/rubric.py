"""Rubric files (rubrics/<lab>.yaml): what is graded, for how many points, with which thresholds."""
import os

import yaml

RUBRIC_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'rubrics')
DEFAULT_LIMITS = {'build_seconds': 240, 'run_seconds': 60, 'stop_seconds': 5}


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

    def get(self, key, default=None):
        return self.settings.get(key, default)


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
        self.limits = dict(DEFAULT_LIMITS, **(data.get('limits') or {}))
        if not isinstance(data['criteria'], list) or not data['criteria']:
            raise RubricError('%s: criteria must be a non-empty list' % path)
        self.criteria = [Criterion(entry, '%s, criterion %d' % (path, number))
                         for number, entry in enumerate(data['criteria'], 1)]
        ids = [c.id for c in self.criteria]
        duplicates = sorted({i for i in ids if ids.count(i) > 1})
        if duplicates:
            raise RubricError('%s: criterion ids used twice: %s' % (path, ', '.join(duplicates)))

    @property
    def max_score(self):
        return sum(c.points for c in self.criteria)

    def criterion(self, criterion_id):
        for criterion in self.criteria:
            if criterion.id == criterion_id:
                return criterion
        raise KeyError(criterion_id)


def labs(rubric_dir=RUBRIC_DIR):
    """The labs that have a rubric, sorted."""
    return sorted(name[:-5] for name in os.listdir(rubric_dir) if name.endswith('.yaml'))


def load(lab_or_path, rubric_dir=RUBRIC_DIR):
    """The rubric of a lab (by name) or of a YAML file (by path)."""
    path = lab_or_path if lab_or_path.endswith('.yaml') else os.path.join(rubric_dir, lab_or_path + '.yaml')
    if not os.path.isfile(path):
        raise RubricError('no rubric for lab %r (the labs are: %s)' % (lab_or_path, ', '.join(labs(rubric_dir))))
    try:
        with open(path) as stream:
            data = yaml.safe_load(stream)
    except yaml.YAMLError as error:
        raise RubricError('%s is not valid YAML: %s' % (path, error))
    return Rubric(data, path)
