"""A student's result in Gradescope's results.json format (pure: no ROS, no files but the one written).

Gradescope reads /autograder/results/results.json: `score`, `output`, `tests[]` with `name`,
`score`, `max_score`, `status` (`passed`/`failed`), `output`, `visibility`."""
import json
import os

RESULTS_FILE = 'results.json'   # Gradescope's name; the grader's own per-student file is result.json


def test_output(criterion):
    """A criterion's reason, then its hints, one a line."""
    lines = [criterion['reason'] or ('passed' if criterion['passed'] else 'failed')]
    lines += ['hint: %s' % hint for hint in criterion.get('hints') or []]
    return '\n'.join(lines)


def from_result(result, visibility='visible'):
    """Gradescope's results.json (a dict) for a result of results.score: one test per criterion."""
    tests = [{'name': '%s (%s)' % (c['title'], c['id']), 'number': str(n),
              'score': c['points'], 'max_score': c['max_points'],
              'status': 'passed' if c['passed'] else 'failed',
              'output': test_output(c), 'visibility': visibility}
             for n, c in enumerate(result['criteria'], 1)]
    output = ['%s: %g / %g' % (result['lab'], result['score'], result['max_score'])]
    if result.get('error'):
        output.append('not fully graded: %s' % result['error'])
    if result.get('pictures'):
        output.append('pictures: %s' % ', '.join(result['pictures']))
    data = {'score': result['score'], 'output': '\n'.join(output), 'output_format': 'text',
            'visibility': visibility, 'tests': tests}
    if result.get('seconds') is not None:
        data['execution_time'] = int(round(result['seconds']))
    return data


def write(result, folder):
    with open(os.path.join(folder, RESULTS_FILE), 'w', encoding='utf-8') as stream:
        json.dump(from_result(result), stream, indent=1, ensure_ascii=False)
