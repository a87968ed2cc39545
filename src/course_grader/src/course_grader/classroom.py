"""A student's result for GitHub Classroom (pure: no ROS), and the assignment's workflow.

GitHub's reporter action (autograding-grading-reporter) reads one base64-encoded JSON object per
runner, from the environment variable <RUNNER>_RESULTS: `version`, `status` (pass, fail, error),
`max_score` and `tests[]` (`name`, `status`, `score`, `message`, `line_no`). It adds up the tests'
`score` and the runners' `max_score` into the points Classroom shows, and prints a table with one
row per runner whose score is max_score times the share of its tests passed. So each criterion of
the rubric is a runner of its own, with one test: every row of the table is then the criterion's
points exactly, whatever the rubric's weights.

A criterion the student may not see yet (results.shown_to_student) still sends its points and
status, which are Classroom's grade, but its message is only the sentence saying it is hidden: the
reporter prints messages and the points table in the run's log, which the student reads."""
import base64
import json
import re

from course_grader import results

GRADE_STEP = 'grade'   # the workflow's grading step: one output per criterion


def inert(text):
    """`text` with no line that a runner takes for a workflow command (`::notice ...::Points 14/14`
    would add an annotation like the reporter's): a reason may quote what the student's code printed
    or named, and the reporter prints an error's message in its log."""
    return re.sub(r'^(\s*):(?=:)', r'\1: ', text, flags=re.MULTILINE)


def criterion_message(criterion, due=None, now=None):
    """What the student reads for a criterion: its reason, then its hints, one a line; for one not
    theirs to see yet, only that it is hidden."""
    if not results.shown_to_student(criterion, due, now):
        return results.HIDDEN[criterion['visibility']]
    lines = [criterion['reason'] or ('passed' if criterion['passed'] else 'failed')]
    lines += ['hint: %s' % hint for hint in criterion.get('hints') or []]
    return inert('\n'.join(lines))


def runner_result(result, criterion, due=None, now=None):
    """The reporter's JSON object (a dict) for one criterion of a result of results.score. A
    submission that could not be graded at all (result['error'] and nothing passed: no package, the
    grading stopped) is an `error`, which the reporter prints with its message."""
    ungraded = bool(result.get('error')) and not any(c['passed'] for c in result['criteria'])
    status = 'pass' if criterion['passed'] else ('error' if ungraded else 'fail')
    return {'version': 1, 'status': status, 'max_score': criterion['max_points'],
            'tests': [{'name': '%s (%s)' % (criterion['title'], criterion['id']), 'status': status,
                       'score': criterion['points'], 'message': criterion_message(criterion, due, now),
                       'line_no': 0}]}


def encode(data):
    return base64.b64encode(json.dumps(data, ensure_ascii=False).encode('utf-8')).decode('ascii')


def decode(text):
    """As the reporter reads a runner's variable."""
    return json.loads(base64.b64decode(text).decode('utf-8'))


def outputs(result, due=None, now=None):
    """The grading step's outputs, {criterion id: the reporter's base64 `result`}, in rubric order
    (`due`: when the rubric's after_due_date criteria are shown)."""
    return {c['id']: encode(runner_result(result, c, due, now)) for c in result['criteria']}


def output_lines(result, due=None, now=None):
    """The lines the grading step appends to $GITHUB_OUTPUT (name=value; base64 has no newline)."""
    return ''.join('%s=%s\n' % item for item in outputs(result, due, now).items())


def points(decoded_runners):
    """Classroom's points from the decoded runners, added up as the reporter does:
    (sum of the tests' score, sum of max_score over the runners that have one)."""
    total = maximum = 0
    for data in decoded_runners:
        if not data.get('max_score'):
            continue
        maximum += data['max_score']
        total += sum(test['score'] for test in data['tests'])
    return total, maximum


def env_name(runner):
    """The variable the reporter reads a runner's result from."""
    return '%s_RESULTS' % runner.strip().upper()


def workflow(template, rubric, image, container_options):
    """The text of .github/workflows/classroom.yml for a lab: the template (platforms/classroom.yml.in)
    with the lab, the image, the grading container's options (one a line, shell-quoted) and a
    reporter runner per criterion filled in."""
    text = template
    ids = [c.id for c in rubric.criteria]
    runner_env = ''.join('          %s: "${{ steps.%s.outputs.%s }}"\n' % (env_name(i), GRADE_STEP, i) for i in ids)
    options = ''.join('            %s \\\n' % option for option in container_options)
    replacements = {'@LAB@': rubric.lab, '@IMAGE@': image, '@PACKAGE@': rubric.package,
                    '@GRADE_STEP@': GRADE_STEP, '@CONTAINER_OPTIONS@\n': options,
                    '@RUNNER_ENV@\n': runner_env, '@RUNNERS@': ','.join(ids)}
    for key, value in replacements.items():
        text = text.replace(key, value)
    return text
