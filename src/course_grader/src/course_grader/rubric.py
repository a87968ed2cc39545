"""Rubric files (rubrics/<lab>.yaml): what is graded, for how many points, with which thresholds,
what the student may see of each criterion (`visibility`) and the late-work policy (`late`)."""
import datetime
import math
import os

import rospkg
import yaml

from course_grader.labs import LABS, lab_module

LIMITS = ('build_seconds', 'run_seconds', 'start_seconds', 'stop_seconds')
# Gradescope's words for who sees a test (tests[].visibility of its results.json); the student's
# check and a Classroom run show a criterion in full only when it is visible (or after_due_date
# once the deadline has passed).
VISIBILITIES = ('visible', 'hidden', 'after_due_date', 'after_published')
LATE_KEYS = ('deadline', 'grace_minutes', 'per_day', 'cap')
DAY = datetime.timedelta(days=1)


def rubric_dir():
    """The package's rubrics/: in the source tree or in the install space, wherever it was found."""
    return os.path.join(rospkg.RosPack().get_path('course_grader'), 'rubrics')


class RubricError(Exception):
    """A rubric file a teacher edited cannot be used: the message says where and why."""


def parse_deadline(value, where='the deadline'):
    """A deadline as an aware datetime: ISO 8601 with a timezone (2026-12-01T23:59+01:00, or Z for
    UTC), as text or as YAML's own timestamp; a RubricError saying why for anything else."""
    if isinstance(value, datetime.datetime):
        when = value
    elif isinstance(value, str):
        try:
            when = datetime.datetime.fromisoformat(value.strip().replace('Z', '+00:00').replace('z', '+00:00'))
        except ValueError:
            raise RubricError('%s %r is not a time in ISO 8601 (give it as 2026-12-01T23:59+01:00)' % (where, value))
    else:
        raise RubricError('%s must be a time in ISO 8601 with its timezone (2026-12-01T23:59+01:00), not %r'
                          % (where, value))
    if when.tzinfo is None or when.utcoffset() is None:
        raise RubricError('%s %s has no timezone: give one (2026-12-01T23:59+01:00, or Z for UTC)' % (where, value))
    return when


class LatePolicy:
    """The rubric's `late:` section: the deadline (None: nothing is late), the grace period, and the
    penalty in percent of the maximum score per day late (each started 24 h after deadline + grace),
    at most `cap` percent."""

    def __init__(self, entry, where):
        if not isinstance(entry, dict):
            raise RubricError('%s: late must be a mapping (%s)' % (where, ', '.join(LATE_KEYS)))
        unknown = sorted(str(key) for key in entry if key not in LATE_KEYS)
        missing = [key for key in LATE_KEYS if key not in entry]
        if unknown or missing:
            raise RubricError('%s: late %s (a late policy gives %s)' % (where, '; '.join(
                (['has no %s' % ', '.join(missing)] if missing else [])
                + (['gives %s, which the grader does not read' % ', '.join(unknown)] if unknown else [])),
                ', '.join(LATE_KEYS)))
        deadline = entry['deadline']
        self.deadline = None if deadline in (None, '') else parse_deadline(deadline, '%s: late.deadline' % where)
        for key, top in (('grace_minutes', None), ('per_day', 100), ('cap', 100)):
            value = entry[key]
            if isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0 \
                    or (top is not None and value > top):
                allowed = ('a number from 0 to %d (percent of the maximum score)' % top if top
                           else 'a number of minutes, 0 or more')
                raise RubricError('%s: late.%s must be %s, not %r' % (where, key, allowed, value))
        self.grace = datetime.timedelta(minutes=entry['grace_minutes'])
        self.per_day = entry['per_day']
        self.cap = entry['cap']
        self.due()   # a deadline so late that the grace cannot be added is refused here

    def due(self):
        """When work starts being late: the deadline plus the grace period (None: never)."""
        try:
            return None if self.deadline is None else self.deadline + self.grace
        except OverflowError:
            raise RubricError('the deadline %s plus late.grace_minutes is beyond the last time a date can '
                              'hold' % self.deadline.isoformat())

    def with_deadline(self, deadline):
        """The same policy with another deadline (the teacher's --deadline)."""
        policy = LatePolicy.__new__(LatePolicy)
        policy.__dict__.update(self.__dict__, deadline=deadline)
        policy.due()
        return policy

    def days_late(self, submitted):
        """Days late of a submission made at `submitted` (aware): 0 up to deadline + grace, then 1 for
        each 24 h begun after it."""
        if self.deadline is None or submitted <= self.due():
            return 0
        return -((self.due() - submitted) // DAY)

    def penalty_percent(self, days):
        return min(self.cap, self.per_day * days)


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
        self.visibility = entry.get('visibility', 'visible')
        if self.visibility not in VISIBILITIES:
            raise RubricError('%s: visibility of %r must be one of %s, not %r' % (
                where, self.id, ', '.join(VISIBILITIES), self.visibility))
        self.settings = {k: v for k, v in entry.items() if k not in ('id', 'title', 'points', 'visibility')}

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
        # No late: section is a policy with no deadline; --deadline then needs the section's numbers.
        self.late = LatePolicy(data['late'], path) if data.get('late') is not None else None

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

    def check_drawn(self, drawn):
        """Refuse bounds the grader draws a number between at each grading (`drawn`: the lab's
        (criterion id, setting) pairs) unless they are [low, high], numbers with 0 < low <= high."""
        for criterion_id, key in drawn:
            bounds = self.criterion(criterion_id).settings[key]
            if not (isinstance(bounds, list) and len(bounds) == 2
                    and all(isinstance(b, (int, float)) and not isinstance(b, bool) and math.isfinite(b) for b in bounds)
                    and 0 < bounds[0] <= bounds[1]):
                raise RubricError('%s: %s of criterion %s must be [low, high], two numbers with 0 < low <= high (the '
                                  'grader draws one between them at each grading), not %r' % (
                                      self.path, key, criterion_id, bounds))

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
    rubric.check_drawn(getattr(lab, 'DRAWN', ()))
    return rubric
