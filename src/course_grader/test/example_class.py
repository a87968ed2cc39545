"""The example classes (examples/grading/<lab>/) and what the grader must give them
(expected.yaml): shared by the container test and the --no-container rostest."""
import csv
import json
import os
import subprocess

import yaml

from course_grader import rubric as rubrics
from course_grader.submission import safe_name

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..', '..'))
EXAMPLES = os.path.join(ROOT, 'examples', 'grading')


def labs():
    return sorted(lab for lab in os.listdir(EXAMPLES)
                  if os.path.isfile(os.path.join(EXAMPLES, lab, 'expected.yaml')))


def expected(lab):
    with open(os.path.join(EXAMPLES, lab, 'expected.yaml')) as stream:
        return yaml.safe_load(stream)


def make_class(lab, folder):
    """The class as a teacher gets it (examples/grading/make_class.py): {student: folder}."""
    listing = subprocess.run([os.path.join(EXAMPLES, 'make_class.py'), lab, folder], stdout=subprocess.PIPE,
                             universal_newlines=True, check=True).stdout
    return {os.path.basename(path): path for path in listing.split()}


def outscored_twins(lab, rows):
    """Hostile students that scored more than their honest twin, as sentences (empty: none did)."""
    return ['%s: %s, more than its twin %s: %s' % (student, rows[student]['score'], wanted['twin'],
                                                    rows[wanted['twin']]['score'])
            for student, wanted in sorted(expected(lab).items())
            if 'twin' in wanted and student in rows and float(rows[student]['score']) > float(rows[wanted['twin']]['score'])]


def edited_rubric(lab, path, edit):
    """The lab's rubric as edit(data) leaves it, written to `path` (for --rubric): returns path."""
    with open(rubrics.load(lab).path) as stream:
        data = yaml.safe_load(stream)
    edit(data)
    with open(path, 'w') as stream:
        yaml.safe_dump(data, stream)
    return path


def read_results(out):
    """grades.csv rows and result.json of every student, by student."""
    with open(os.path.join(out, 'grades.csv'), encoding='utf-8') as stream:
        rows = {row['student']: row for row in csv.DictReader(stream)}
    details = {}
    for student, row in rows.items():
        folder = '%s_%s' % (safe_name(student), row['id']) if row['id'] else safe_name(student)
        with open(os.path.join(out, folder, 'result.json'), encoding='utf-8') as stream:
            details[student] = json.load(stream)
    return rows, details


def sentences_of(result, criterion_id):
    criterion = next(c for c in result['criteria'] if c['id'] == criterion_id)
    return '\n'.join([criterion['reason']] + criterion['hints'])


def mismatches(lab, rows, details, students):
    """What differs from expected.yaml, as sentences (empty: all as expected)."""
    found = []
    for student in students:
        wanted = expected(lab)[student]
        if float(rows[student]['score']) != wanted['score']:
            found.append('%s: score %s, expected %s; criteria: %s' % (
                student, rows[student]['score'], wanted['score'],
                [(c['id'], c['points'], c['reason'], c['hints']) for c in details[student]['criteria']]))
        for criterion_id, sentence in (wanted.get('sentences') or {}).items():
            said = sentences_of(details[student], criterion_id)
            if sentence not in said:
                found.append('%s, %s: expected %r in %r' % (student, criterion_id, sentence, said))
    return found
