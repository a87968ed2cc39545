"""A student's result: one outcome per rubric criterion, the score, and what the sandbox left; the
late-work penalty (with_late) on top: `raw_score` is the criteria's sum, `score` the final one."""
import datetime
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
            'visibility': criterion.visibility,
            'reason': '' if outcome.passed and not outcome.reason else outcome.reason,
            'hints': outcome.hints})
    total = sum(c['points'] for c in criteria)
    return {'student': student, 'lab': rubric.lab, 'score': total, 'raw_score': total, 'late': None,
            'max_score': rubric.max_score, 'error': error, 'criteria': criteria,
            'pictures': list(pictures), 'seconds': seconds}


# What the student reads of a criterion that is not theirs to see yet (rubric.VISIBILITIES).
HIDDEN = {'hidden': 'hidden until the teacher publishes it',
          'after_published': 'hidden until the teacher publishes the grades',
          'after_due_date': 'hidden until the deadline has passed'}


def shown_to_student(criterion, due=None, now=None):
    """Whether the student may read a criterion of a result (its points, reason and hints): a visible
    one always, an after_due_date one once `due` (the rubric's deadline and grace, aware) has passed,
    never a hidden or after_published one."""
    visibility = criterion.get('visibility', 'visible')
    if visibility == 'after_due_date' and due is not None:
        return (now or datetime.datetime.now(datetime.timezone.utc)) >= due
    return visibility == 'visible'


def shown_total(result, due=None, now=None):
    """(points, max points, criteria hidden) over what the student may see of a result."""
    shown = [c for c in result['criteria'] if shown_to_student(c, due, now)]
    return (sum(c['points'] for c in shown), sum(c['max_points'] for c in shown),
            len(result['criteria']) - len(shown))


def with_late(result, policy, submitted):
    """The result with the late-work penalty of `policy` (rubric.LatePolicy, with a deadline) taken
    off: `late` says when it was submitted, by what source (a submission.Submitted) and what it cost;
    `score` is then raw_score less the penalty, never below 0. Without a known time nothing is taken
    and `late` says why."""
    raw = result['raw_score']
    late = {'deadline': policy.deadline.isoformat(), 'grace_minutes': policy.grace.total_seconds() / 60,
            'submitted': None, 'source': submitted.source, 'claim': submitted.claim,
            'days_late': 0, 'penalty_percent': 0, 'penalty': 0}
    if submitted.time is not None:
        days = policy.days_late(submitted.time)
        percent = policy.penalty_percent(days)
        penalty = round(min(raw, result['max_score'] * percent / 100.0), 4)
        late.update(submitted=submitted.time.isoformat(), days_late=days, penalty_percent=percent, penalty=penalty)
    return dict(result, late=late, score=round(raw - late['penalty'], 4))


CLAIM = 'a claim of the student\'s own git, which the student can forge'


def late_source(late):
    """Where the submission time of a result's `late` was read, saying when it is the student's claim."""
    return '%s (%s)' % (late['source'], CLAIM) if late['claim'] and late['submitted'] else late['source']


def describe_late(late):
    """One sentence on a result's `late` (None: no late policy, ''), for the terminal and the report."""
    if not late:
        return ''
    if late['submitted'] is None:
        return 'submission time unknown (%s): no late penalty' % late['source']
    claim = ': %s' % CLAIM if late['claim'] else ''
    if not late['days_late']:
        return 'submitted %s (%s%s): on time' % (late['submitted'], late['source'], claim)
    return 'submitted %s (%s%s): %d day%s late, -%g%% of the maximum: -%g points' % (
        late['submitted'], late['source'], claim, late['days_late'], '' if late['days_late'] == 1 else 's',
        late['penalty_percent'], late['penalty'])


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
        result = score(rubric, outcomes, student, error=str(error) if error else None, pictures=pictures)
        # What the session noted beside the grade (a run it could not keep as a bag, say).
        result['notes'] = [note[:500] for note in data.get('notes', []) if isinstance(note, str)][:20]
        return result
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
