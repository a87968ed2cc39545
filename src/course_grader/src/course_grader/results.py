"""A student's result: one outcome per rubric criterion, the score, and what the sandbox left."""
import json
import os

from course_checks.verdict import Verdict

RESULT_FILE = 'result.json'


def score(rubric, outcomes, student, error=None, pictures=(), seconds=None):
    """The result (a dict, as written to result.json) of a student for a rubric. Criteria without
    an outcome (the run stopped before them) get 0 points with `error` as their reason."""
    criteria = []
    for criterion in rubric.criteria:
        outcome = outcomes.get(criterion.id) or Verdict(False, error or 'not checked')
        criteria.append({
            'id': criterion.id, 'title': criterion.title, 'max_points': criterion.points,
            'points': criterion.points if outcome.passed else 0, 'passed': outcome.passed,
            'reason': '' if outcome.passed and not outcome.reason else outcome.reason,
            'hints': outcome.hints})
    return {'student': student, 'lab': rubric.lab, 'score': sum(c['points'] for c in criteria),
            'max_score': rubric.max_score, 'error': error, 'criteria': criteria,
            'pictures': list(pictures), 'seconds': seconds}


def failed(rubric, student, reason, seconds=None):
    """The result of a submission that could not be graded at all (not built, refused, timed out)."""
    return score(rubric, {}, student, error=reason, seconds=seconds)


def write(result, folder):
    with open(os.path.join(folder, RESULT_FILE), 'w') as stream:
        json.dump(result, stream, indent=1, sort_keys=True)


def read(rubric, student, folder):
    """A result.json the sandbox wrote, checked against the rubric (the sandbox is the student's:
    never trust its numbers beyond what the rubric allows)."""
    path = os.path.join(folder, RESULT_FILE)
    try:
        with open(path) as stream:
            data = json.load(stream)
        by_id = {c['id']: c for c in data['criteria']}
        outcomes = {cid: Verdict(c['passed'] is True, str(c.get('reason', ''))[:4000],
                                 [str(h)[:4000] for h in c.get('hints', [])][:20])
                    for cid, c in by_id.items() if cid in {c.id for c in rubric.criteria}}
        pictures = [p for p in data.get('pictures', []) if isinstance(p, str)
                    and os.path.basename(p) == p and p.endswith('.png')]
        error = data.get('error')
        return score(rubric, outcomes, student, error=str(error) if error else None, pictures=pictures)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def read_earlier(out):
    """The results a grading into `out` left, by student folder (unreadable ones left out)."""
    earlier = {}
    for name in sorted(os.listdir(out)):
        try:
            with open(os.path.join(out, name, RESULT_FILE)) as stream:
                result = json.load(stream)
            earlier[name] = {'student': str(result.get('student', name)), 'score': float(result['score']),
                             'max_score': float(result['max_score']),
                             'criteria': {str(c['id']): float(c['points']) for c in result['criteria']}}
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            continue
    return earlier


def change(before, after):
    """What changed for a student since the earlier grading (an entry of read_earlier, or None):
    None for a student new to this folder, else the scores and the criteria whose points changed."""
    if before is None:
        return None
    now = {c['id']: c['points'] for c in after['criteria']}
    changed = [(cid, before['criteria'].get(cid, 0.0), points) for cid, points in now.items()
               if before['criteria'].get(cid, 0.0) != points]
    return {'score_before': before['score'], 'score': after['score'], 'max_score': after['max_score'],
            'criteria': changed}


def describe_change(changed):
    """One phrase for the terminal: '' for a first grading, else what the earlier one gave."""
    if changed is None:
        return ''
    if not changed['criteria']:
        return '; as before'
    return '; before %g / %g: %s' % (changed['score_before'], changed['max_score'], ', '.join(
        '%s %g -> %g' % item for item in changed['criteria']))
