"""A student's result in Gradescope's results.json format (pure: no ROS, no files but the one written).

Gradescope reads /autograder/results/results.json: `score`, `output`, `tests[]` with `name`,
`score`, `max_score`, `status` (`passed`/`failed`), `output`, `visibility` (each test's is its
criterion's in the rubric: Gradescope shows it to the student accordingly). `score` is the final
score: with ./grade.sh's late policy, the criteria's sum less the penalty; the platform's own
grading (grade_platform) applies none, Gradescope taking off its own late penalty."""
import json
import os

from course_grader.results import describe_late

RESULTS_FILE = 'results.json'   # Gradescope's name; the grader's own per-student file is result.json


def test_output(criterion):
    """A criterion's reason, then its hints, one a line."""
    lines = [criterion['reason'] or ('passed' if criterion['passed'] else 'failed')]
    lines += ['hint: %s' % hint for hint in criterion.get('hints') or []]
    return '\n'.join(lines)


def from_result(result, visibility='visible'):
    """Gradescope's results.json (a dict) for a result of results.score: one test per criterion;
    `visibility` is the whole result's."""
    tests = [{'name': '%s (%s)' % (c['title'], c['id']), 'number': str(n),
              'score': c['points'], 'max_score': c['max_points'],
              'status': 'passed' if c['passed'] else 'failed',
              'output': test_output(c), 'visibility': c.get('visibility', 'visible')}
             for n, c in enumerate(result['criteria'], 1)]
    output = ['%s: %g / %g' % (result['lab'], result['score'], result['max_score'])]
    if result.get('late') and result['late']['penalty']:
        output.append('%g / %g before the late penalty: %s' % (result['raw_score'], result['max_score'],
                                                               describe_late(result['late'])))
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
