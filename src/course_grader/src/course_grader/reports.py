"""The class's report: grades.csv (one row per student), junit/<student>.xml (one testcase per
criterion), report.html (a section per student: rubric, reasons, pictures, log tails)."""
import base64
import csv
import html
import os
import xml.etree.ElementTree as ET

from course_grader import feedback, replay, results as course_results, similarity
from course_grader.submission import spreadsheet_cell


def _points(value):
    return ('%g' % value) if isinstance(value, (int, float)) else str(value)


def folder_of(result):
    """The student's folder in --out (the name, made safe for a path, and the platform's id)."""
    return result.get('folder') or result['student']




# After the criteria, what late work cost (results.with_late): empty without a late policy.
LATE_COLUMNS = ['raw_score', 'late_penalty', 'days_late', 'submitted', 'submitted_from']


def _late_cells(result):
    late = result.get('late')
    raw = result.get('raw_score', result['score'])
    if not late:
        return [raw, '', '', '', '']
    return [raw, late['penalty'], late['days_late'], late['submitted'] or '', course_results.late_source(late)]


def write_csv(results, rubric, path):
    """One row per student: the name as the platform wrote it, its id there (the column a grade
    book matches rows by), the (final) score and each criterion's points, then the score before
    the late penalty and what the penalty was made of (LATE_COLUMNS)."""
    with open(path, 'w', newline='', encoding='utf-8') as stream:
        writer = csv.writer(stream)
        writer.writerow([spreadsheet_cell(name) for name in ['student', 'id', 'lab', 'score', 'max_score']
                         + [c.id for c in rubric.criteria] + LATE_COLUMNS])
        for result in sorted(results, key=lambda r: r['student']):
            points = {c['id']: c['points'] for c in result['criteria']}
            cells = [result['student'], result.get('student_id', ''), result['lab'], result['score'],
                     result['max_score']] + [points.get(c.id, 0) for c in rubric.criteria] + _late_cells(result)
            writer.writerow([spreadsheet_cell(cell) for cell in cells])


def _failure_text(criterion):
    return '\n'.join([criterion['reason']] + criterion['hints']).strip()


def junit_xml(result):
    """JUnit XML of a student's result: a testsuite named after the student, a testcase per
    criterion, failed with the reason (what CI servers and GitHub Classroom read)."""
    failures = sum(1 for c in result['criteria'] if not c['passed'])
    suite = ET.Element('testsuite', name='%s.%s' % (result['lab'], result['student']),
                       tests=str(len(result['criteria'])), failures=str(failures), errors='0',
                       time='%.1f' % (result.get('seconds') or 0))
    for criterion in result['criteria']:
        case = ET.SubElement(suite, 'testcase', classname='%s.%s' % (result['lab'], result['student']),
                             name=criterion['id'])
        ET.SubElement(case, 'properties')
        properties = case.find('properties')
        for name, value in (('points', criterion['points']), ('max_points', criterion['max_points']),
                            ('title', criterion['title'])):
            ET.SubElement(properties, 'property', name=name, value=_points(value))
        if not criterion['passed']:
            text = _failure_text(criterion)
            failure = ET.SubElement(case, 'failure', message=text.splitlines()[0] if text else 'failed')
            failure.text = text
    return ET.tostring(suite, encoding='unicode')


def write_junit(result, folder):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, folder_of(result) + '.xml'), 'w', encoding='utf-8') as stream:
        stream.write('<?xml version="1.0" encoding="UTF-8"?>\n' + junit_xml(result) + '\n')


CSS = '''
body { font-family: sans-serif; margin: 2em; color: #222; max-width: 70em; }
table { border-collapse: collapse; margin: 0.5em 0; }
/* A table wider than a phone scrolls in its own box; the page itself never scrolls sideways. */
.wide { overflow-x: auto; max-width: 100%; }
.summary td:first-child, .summary th:first-child { position: sticky; left: 0; background: #fff; }
.summary th:first-child { background: #eee; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #eee; }
td.pass { color: #161; } td.fail { color: #a11; }
.summary td.num, td.num { text-align: right; white-space: nowrap; }
pre { background: #f6f6f6; padding: 0.5em; max-height: 20em; overflow: auto; font-size: 85%; }
.pictures img { max-width: min(22em, 90vw); border: 1px solid #ccc; margin: 0.3em; }
.error { color: #a11; font-weight: bold; }
td.why { white-space: pre-wrap; overflow-wrap: anywhere; }
@media (max-width: 40em) { body { margin: 0.6em; } }
'''


def html_report(results, rubric, out_dir, seconds=None, previous=None, log_lines=25):
    """The HTML page of a graded class (pictures embedded, so the file can be mailed alone); with
    previous (results.read_earlier of the same --out), what changed since that grading."""
    previous = previous or {}
    esc = html.escape
    results = sorted(results, key=lambda r: r['student'])
    parts = ['<!DOCTYPE html><html><head><meta charset="utf-8">'
             '<meta name="viewport" content="width=device-width, initial-scale=1"><title>%s: grades</title><style>%s</style>'
             '</head><body>' % (esc(rubric.lab), CSS),
             '<h1>%s</h1><p>Lab <code>%s</code>, %d students, out of %s points%s. Rubric: <code>%s</code>.</p>'
             % (esc(rubric.title), esc(rubric.lab), len(results), _points(rubric.max_score),
                ', graded in %.0f s' % seconds if seconds is not None else '',
                esc(os.path.basename(rubric.path)))]
    late = any(r.get('late') for r in results)
    parts.append('<div class="wide"><table class="summary"><tr><th>student</th><th>id</th><th>score</th>%s%s%s</tr>' % (
        '<th>before the late penalty</th><th>late</th>' if late else '', '<th>before</th>' if previous else '',
        ''.join('<th title="%s">%s</th>' % (esc(c.title), esc(c.id)) for c in rubric.criteria)))
    for result in results:
        cells = ''.join('<td class="%s num">%s</td>' % ('pass' if c['passed'] else 'fail', _points(c['points']))
                        for c in result['criteria'])
        earlier = previous.get(folder_of(result))
        before = ('<td class="num">%s</td>' % ('%s / %s' % (_points(earlier['score']), _points(earlier['max_score']))
                                              if earlier else 'new') if previous else '')
        lateness = ('<td class="num">%s</td><td class="num">%s</td>' % (
            _points(result.get('raw_score', result['score'])), _late_summary(result.get('late'))) if late else '')
        parts.append('<tr><td><a href="#%s">%s</a></td><td>%s</td><td class="num">%s / %s</td>%s%s%s</tr>' % (
            esc(folder_of(result)), esc(result['student']), esc(result.get('student_id', '')),
            _points(result['score']), _points(result['max_score']), lateness, before, cells))
    parts.append('</table></div>')
    gone = sorted(set(previous) - {folder_of(r) for r in results})
    if gone:
        parts.append('<p>Graded last time into this folder, not this time: %s.</p>' % ', '.join(
            '%s (%s / %s)' % (esc(previous[f]['student']), _points(previous[f]['score']),
                              _points(previous[f]['max_score'])) for f in gone))
    for result in results:
        student = result['student']
        folder = os.path.join(out_dir, folder_of(result))
        parts.append('<h2 id="%s">%s: %s / %s</h2>' % (esc(folder_of(result)), esc(student), _points(result['score']),
                                                       _points(result['max_score'])))
        changed = results_change(previous, result)
        if changed:
            parts.append('<p class="change">%s</p>' % esc(changed))
        if result.get('late'):
            parts.append('<p class="late">Late work: %s.%s</p>' % (
                esc(course_results.describe_late(result['late'])), ' Score %s / %s before the penalty, %s after it.' % (
                    _points(result['raw_score']), _points(result['max_score']), _points(result['score']))
                if result['late']['penalty'] else ''))
        if result.get('error'):
            parts.append('<p class="error">%s</p>' % esc(result['error']))
        for note in result.get('notes', []):
            parts.append('<p class="note">Note: %s</p>' % esc(note))
        parts.append('<div class="wide"><table><tr><th>criterion</th><th>points</th><th>why</th></tr>')
        for c in result['criteria']:
            why = _failure_text(c) or 'ok'   # hints too when it passed (a node that ignores Ctrl-C)
            seen = '' if c.get('visibility', 'visible') == 'visible' else ' (%s for the student)' % c['visibility']
            parts.append('<tr><td>%s</td><td class="%s num">%s / %s</td><td class="why">%s</td></tr>' % (
                esc(c['title'] + seen), 'pass' if c['passed'] else 'fail', _points(c['points']),
                _points(c['max_points']), esc(why)))
        parts.append('</table></div>')
        pictures = [p for p in result.get('pictures', []) if os.path.isfile(os.path.join(folder, p))]
        if pictures:
            parts.append('<div class="pictures">')
            for picture in pictures:
                with open(os.path.join(folder, picture), 'rb') as stream:
                    data = base64.b64encode(stream.read()).decode('ascii')
                parts.append('<figure style="display:inline-block"><img alt="%s" src="data:image/png;base64,%s">'
                             '<figcaption>%s</figcaption></figure>' % (esc(picture), data, esc(picture)))
            parts.append('</div>')
        parts.append(replay.runs_html(out_dir, folder_of(result)))   # each run played back
        for log in sorted(n for n in os.listdir(folder) if n.endswith('.log')) if os.path.isdir(folder) else []:
            tail = feedback.log_tail(os.path.join(folder, log), log_lines)
            if tail:
                parts.append('<details><summary>%s (last %d lines; whole log in %s/%s)</summary><pre>%s</pre>'
                             '</details>' % (esc(log), log_lines, esc(folder_of(result)), esc(log), esc(tail)))
    parts.append(replay.PAGE_PARTS)
    parts.append(similarity.html_section(out_dir))
    parts.append('</body></html>')
    return '\n'.join(parts)


def _late_summary(late):
    """The class table's late cell: '-2.8 (2 d)', 'on time', 'no time' or '' without a policy."""
    if not late:
        return ''
    if late['submitted'] is None:
        return 'no time'
    return '-%s (%d d)' % (_points(late['penalty']), late['days_late']) if late['days_late'] else 'on time'


def results_change(previous, result):
    """The sentence of report.html on what changed since the earlier grading, or ''."""
    if not previous:
        return ''
    changed = course_results.change(previous.get(folder_of(result)), result)
    if changed is None:
        return 'New: not in the earlier grading into this folder.'
    if not changed['criteria']:
        return 'As in the earlier grading into this folder.'
    return 'The earlier grading into this folder gave %s / %s; changed since: %s.' % (
        _points(changed['score_before']), _points(changed['max_score']),
        ', '.join('%s %s → %s' % (cid, _points(a), _points(b)) for cid, a, b in changed['criteria']))


def write_all(results, rubric, out_dir, seconds=None, previous=None):
    """grades.csv, junit/ and report.html of a class into out_dir (replacing earlier ones)."""
    write_csv(results, rubric, os.path.join(out_dir, 'grades.csv'))
    for result in results:
        write_junit(result, os.path.join(out_dir, 'junit'))
    with open(os.path.join(out_dir, 'report.html'), 'w', encoding='utf-8') as stream:
        stream.write(html_report(results, rubric, out_dir, seconds, previous))
