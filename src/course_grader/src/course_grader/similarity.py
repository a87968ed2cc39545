"""Similar submissions: the pairs of students whose code is more alike than chance, once what every
student is given (the slides' code, the lab's pages, the course's reference package) is taken out.

The comparison is Debian's similarity-tester (Dick Grune's `sim`): `sim_c++` for C and C++ (it
compares tokens: layout, comments, names and the values of numbers and strings do not count) and
`sim_text` for Python (words). It runs twice on copies of the students' source files in a scratch
folder (named by number, so that no student's file name reaches its command line or its output),
each time with a time limit and only its standard output read back, at most MAX_OUTPUT_BYTES of it.
sim is a C program reading what the students wrote: with ./grade.sh's image it runs in a container
of that image (in_container: a grading's sandbox, as `student` without any capability, the copies
mounted read-only), with --no-container on this machine (on_host: the teacher chose no isolation):

1. each student's files against the lab's given files (GIVEN), with runs of half the length of
   step 2's, so that the given code cut short by a student's edits goes too: every run of the
   student's code that is also in the given material is blanked (its lines emptied, so line
   numbers stay). The lines inside a run go; its first and last lines, which the run may cover only
   in part, go only when the line itself (spaces aside) is in the given material, so that a changed
   constant stays;
2. what is left of every student's files against each other's (`-e`: each pair of files on its
   own): each run found between two students' files is shared code.

A pair is listed when it shares at least one run of the language's run_tokens (tokens, words for
Python) beyond the given material; its percentage is the shared tokens over the own code (the
tokens left after step 1) of the one of the two with less of it. Only the students' source files
count (LANGUAGES): at most MAX_FILES of them, each at most MAX_FILE_BYTES and all of them at most
MAX_STUDENT_BYTES, UTF-8 text (a file with a NUL byte or not UTF-8 is left out); links are never
followed."""
import collections
import contextlib
import csv
import glob
import html
import json
import os
import re
import shutil
import stat
import subprocess
import tempfile
import threading
import uuid

from course_common.waiting import poll_until
from course_grader.sandbox import CONTAINER_BASE, CONTAINER_LIMITS, read_at_most, stop_container
from course_grader.submission import SubmissionError, find_package, spreadsheet_cell, student_of, terminal_text, unpack

Language = collections.namedtuple('Language', 'name tool suffixes run_tokens')   # suffixes[0]: its copies'
LANGUAGES = (
    Language('C++', 'sim_c++', ('.cpp', '.c', '.cc', '.cxx', '.h', '.hh', '.hpp', '.hxx'), 24),
    # sim_text's own default is 8 words: too short for ROS's boilerplate (rospy.Subscriber('scan',
    # LaserScan, callback, queue_size=1) is 7 words), which students write alike without copying.
    Language('Python', 'sim_text', ('.py',), 16),
)
MAX_FILES = 50                  # source files read per student (the first ones by path)
MAX_FILE_BYTES = 256 * 1024     # a bigger source file is left out
MAX_STUDENT_BYTES = 1024 * 1024  # a student's files read, at most, in all
TIMEOUT_SECONDS = 300           # each run of sim
MAX_OUTPUT_BYTES = 16 * 2 ** 20  # of each run's standard output (a run line is about 80 bytes)
SUMMARY = ['-n', '-i']           # sim's options of every run: a line per run; the file names from standard input
# A container as a grading's (no network, read-only root, its limits), but as the image's user
# `student` (the later --user wins) and with no capability at all; the copies are mounted read-only.
SIM_CONTAINER = CONTAINER_BASE + ['--user', 'student', '--cap-drop', 'ALL'] + CONTAINER_LIMITS
SHOWN_RUNS = 6                  # runs shown side by side per pair in report.html
SHOWN_LINES = 40                # lines shown of each side of a run

# What every student of a lab is given, under the repository's root: the course's reference package
# (and its README, the lab's page), the slides as printed and as pasted, the lab's copying page.
# Of a .md file, its code blocks count (fenced or indented); name.py.txt is Python, name.cpp.txt C++.
GIVEN = {
    'my_turtle': ['src/my_turtle', 'examples/grading/my_turtle/slides_as_printed',
                  'tests/student/slides/my_turtle_node_stage*.cpp', 'docs/copying-the-slides/my_turtle.md'],
    'ros_exercises': ['src/ros_exercises', 'examples/grading/ros_exercises/slides_as_printed',
                      'tests/student/slides/pasted/*.cpp.txt', 'docs/copying-the-slides/ros_exercises.md'],
    'move_turtlebot3': ['src/move_turtlebot3', 'examples/grading/move_turtlebot3/slides_as_printed',
                        'tests/student/slides/*.py.txt', 'tests/student/slides/pasted/*.py.txt',
                        'docs/copying-the-slides/move_turtlebot3.md'],
}
CSV_NAME = 'similarity.csv'
RESULT_NAME = 'similarity.json'


class SimilarityError(Exception):
    """The comparison could not be made (no sim, a time-out): one sentence for the report."""


def repository_root():
    """The workspace's root, where GIVEN's paths are (this file is src/course_grader/src/course_grader/)."""
    return os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..', '..', '..'))


def language_of(name):
    """The Language of a file name (name.py.txt as name.py), or None."""
    name = name[:-len('.txt')] if name.endswith('.txt') else name
    return next((language for language in LANGUAGES if name.endswith(language.suffixes)), None)


def read_text(path):
    """The text of a regular file (never through a link), or None: not a regular file, bigger than
    MAX_FILE_BYTES, a NUL byte in it, or not UTF-8."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError:
        return None
    with os.fdopen(fd, 'rb') as stream:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > MAX_FILE_BYTES:
            return None
        data = stream.read(MAX_FILE_BYTES + 1)
    if len(data) > MAX_FILE_BYTES or b'\0' in data:
        return None
    try:
        return data.decode('utf-8')
    except UnicodeDecodeError:
        return None


def source_files(folder):
    """[(path relative to folder, Language, text)] of the source files under folder, sorted by path,
    MAX_FILES and MAX_STUDENT_BYTES at most; links (to files or folders) are not followed, hidden
    folders and a workspace's build/ and devel/ are skipped."""
    found, size = [], 0
    for parent, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith('.') and d not in ('build', 'devel'))
        for name in sorted(files):
            language = language_of(name)
            if language is None or name.endswith('.txt'):
                continue
            path = os.path.join(parent, name)
            text = read_text(path)
            if text is None or size + len(text.encode('utf-8')) > MAX_STUDENT_BYTES:
                continue
            size += len(text.encode('utf-8'))
            found.append((os.path.relpath(path, folder), language, text))
            if len(found) >= MAX_FILES:
                return found
    return found


def markdown_code(text):
    """The code blocks of a Markdown page (fenced with ``` or indented by four spaces), as one text."""
    code, fenced = [], False
    for line in text.splitlines():
        if line.lstrip().startswith('```'):
            fenced = not fenced
        elif fenced or line.startswith('    ') or line.startswith('\t'):
            code.append(line)
    return '\n'.join(code) + '\n'


def given_texts(lab):
    """{Language: [text]}: what every student of the lab is given (GIVEN), read from the repository;
    a Markdown page's code blocks count for every language."""
    root = repository_root()
    texts = collections.defaultdict(list)
    for pattern in GIVEN.get(lab, []):
        for path in sorted(glob.glob(os.path.join(root, pattern))):
            paths = [path] if os.path.isfile(path) else [os.path.join(parent, name) for parent, _, names
                                                         in os.walk(path) for name in sorted(names)]
            for file_path in paths:
                text = read_text(file_path)
                if text is None:
                    continue
                if file_path.endswith('.md'):
                    for language in LANGUAGES:
                        texts[language].append(markdown_code(text))
                elif language_of(file_path):
                    texts[language_of(file_path)].append(text)
    return texts


# One run of sim -n: `s1f0.cpp: line 3-20 |g4.cpp: line 1-18 [120]`, our own file names.
RUN_LINE = re.compile(r'^(?P<a>[\w.+-]+): line (?P<a_first>\d+)-(?P<a_last>\d+)\s*\|'
                      r'(?P<b>[\w.+-]+): line (?P<b_first>\d+)-(?P<b_last>\d+)\s*\[(?P<tokens>\d+)\]\s*$')
SIZE_LINE = re.compile(r'^File (?P<name>[\w.+-]+): (?P<tokens>\d+) tokens?, (?P<lines>\d+) lines?\s*$')
Run = collections.namedtuple('Run', 'a a_first a_last b b_first b_last tokens')


def parse_runs(output):
    """The runs of sim's summary output (-n): [Run], in the order printed."""
    runs = []
    for line in output.splitlines():
        match = RUN_LINE.match(line)
        if match:
            runs.append(Run(match['a'], int(match['a_first']), int(match['a_last']), match['b'],
                            int(match['b_first']), int(match['b_last']), int(match['tokens'])))
    return runs


def parse_tokens(output):
    """{file name: tokens} from the `File NAME: N tokens, M lines` lines sim prints first."""
    return {match['name']: int(match['tokens']) for match in map(SIZE_LINE.match, output.splitlines()) if match}


def normal(line):
    """A line as compared with the given material: its spaces do not count."""
    return ''.join(line.split())


def given_lines(runs, lines, given):
    """The line numbers (1-based) of a file's `lines` that the runs against the given material
    cover: every line inside a run, and its first and last line when that line, spaces aside, is
    in `given` (a set of normal() lines), since a run may cover only part of them."""
    covered = set()
    for run in runs:
        covered.update(range(run.a_first + 1, run.a_last))
        covered.update(n for n in {run.a_first, run.a_last}
                       if 1 <= n <= len(lines) and normal(lines[n - 1]) in given)
    return covered


def on_host(tool, arguments, names, folder):
    """sim's output on the files `names` in folder, run on this machine (--no-container); a
    SimilarityError when it is missing, fails, takes too long or says too much."""
    if shutil.which(tool) is None:
        raise SimilarityError('%s is not installed (Debian 12\'s package similarity-tester, which tools/setup.sh '
                              'installs; Debian 13 does not carry it)' % tool)

    def stop(process):
        if process.poll() is None:
            process.kill()
            process.wait()
    return _output(tool, [tool] + SUMMARY + arguments, names, stop, cwd=folder)


def in_container(image):
    """A runner like on_host that runs sim in a container of image (SIM_CONTAINER), folder mounted
    read-only as its working folder."""
    def run(tool, arguments, names, folder):
        name = 'course-grader-similarity-%s' % uuid.uuid4().hex[:12]
        command = (['docker', 'run', '--interactive', '--name', name] + SIM_CONTAINER
                   + ['-v', '%s:/compared:ro' % os.path.abspath(folder), '--workdir', '/compared', '--entrypoint', tool,
                      image] + SUMMARY + arguments)
        return _output(tool, command, names, lambda process: stop_container(name, process), image=image)
    return run


def _output(tool, command, names, stop, image=None, **popen_args):
    """The standard output of sim started with `command`, `names` on its standard input; stop(process)
    ends it, whatever happened. A SimilarityError when it prints more than MAX_OUTPUT_BYTES (stopped
    then), takes more than TIMEOUT_SECONDS or fails (127 in a container of `image`: the image has no sim)."""
    output, errors = bytearray(), bytearray()
    process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               **popen_args)
    threads = [threading.Thread(target=_write_names, args=(process.stdin, names), daemon=True),
               threading.Thread(target=read_at_most, args=(process.stdout, output, MAX_OUTPUT_BYTES + 1), daemon=True),
               threading.Thread(target=read_at_most, args=(process.stderr, errors, 4096), daemon=True)]
    for thread in threads:
        thread.start()
    try:
        poll_until(lambda: process.poll() is not None or len(output) > MAX_OUTPUT_BYTES, TIMEOUT_SECONDS, poll=0.05)
    finally:
        code = process.poll()
        stop(process)
        for thread in threads:
            thread.join(10)
    if len(output) > MAX_OUTPUT_BYTES:
        raise SimilarityError('%s printed more than %d MB' % (tool, MAX_OUTPUT_BYTES // 2 ** 20))
    if code is None:
        raise SimilarityError('%s did not finish in %d s' % (tool, TIMEOUT_SECONDS))
    if code == 127 and image:
        raise SimilarityError('%s is not in the course\'s image (made before tools/debian-packages.txt listed '
                              'similarity-tester: ./grade.sh makes it again)' % tool)
    if code != 0:
        raise SimilarityError('%s failed (exit status %d): %s' % (tool, code, terminal_text(
            errors.decode(errors='replace').strip()[-300:])))
    return output.decode(errors='replace')


def _write_names(pipe, names):
    """The file names, a line each, to sim's standard input, and its end (a sim that ended early: its
    exit status says why)."""
    with contextlib.suppress(BrokenPipeError):
        pipe.write(('\n'.join(names) + '\n').encode())
    with contextlib.suppress(BrokenPipeError):
        pipe.close()


def compare(students, given, folder, sim=on_host):
    """The pairs of students whose own code is alike, best first. students: {student: [(path,
    Language, text)]}; given: {Language: [text]}; folder: an empty scratch folder; sim: on_host or
    in_container(image)'s runner. Each pair:
    {'a', 'b' (students, a before b in the order of students), 'percent', 'shared_lines', 'runs':
    [{'tokens', 'a', 'b': {'path', 'first' (line), 'lines', 'given' (those of the lines that are
    given material, by index)}}], longest first}."""
    order = list(students)
    shared = collections.defaultdict(list)
    own_tokens = collections.Counter()
    for language in LANGUAGES:
        files = {}   # our name: (student index, path, lines)
        for index, student in enumerate(order):
            for number, (path, file_language, text) in enumerate(students[student]):
                if file_language == language:
                    files['s%df%d%s' % (index, number, language.suffixes[0])] = (index, path, text.splitlines())
        if not files:
            continue
        own = _without_given(files, given.get(language, []), language, folder, sim)
        output = sim(language.tool, ['-e', '-s', '-r', str(language.run_tokens)], sorted(files), folder)
        for name, tokens in parse_tokens(output).items():
            if name in files:
                own_tokens[files[name][0]] += tokens
        for run in parse_runs(output):
            sides = sorted([(files[run.a][0], run.a, run.a_first, run.a_last),
                            (files[run.b][0], run.b, run.b_first, run.b_last)])
            (a, *a_side), (b, *b_side) = sides
            if a != b:   # not a student's own files alike
                shared[a, b].append({'tokens': run.tokens, 'a': _side(files, own, *a_side),
                                     'b': _side(files, own, *b_side)})
    pairs = []
    for (a, b), runs in shared.items():
        tokens = sum(run['tokens'] for run in runs)
        smaller = min(own_tokens[a], own_tokens[b]) or tokens
        own_lines = {(run['a']['path'], run['a']['first'] + n) for run in runs
                     for n, line in enumerate(run['a']['lines']) if line.strip() and n not in run['a']['given']}
        pairs.append({'a': order[a], 'b': order[b], 'percent': min(100, round(100 * tokens / smaller)),
                      'shared_lines': len(own_lines), 'runs': sorted(runs, key=lambda run: -run['tokens'])})
    return sorted(pairs, key=lambda pair: (-pair['percent'], -pair['shared_lines'], pair['a'], pair['b']))


def _without_given(files, given, language, folder, sim):
    """Writes each of files (our name: (student, path, lines)) into folder with the lines it shares
    with the given texts blanked (step 1 of the module's docstring); returns {our name: lines left,
    '' for the given ones}."""
    given_names = ['g%d%s' % (number, language.suffixes[0]) for number in range(len(given))]
    against_given = collections.defaultdict(list)
    if given:
        for name, text in zip(given_names, given):
            _write_lines(folder, name, text.splitlines())
        for name, (_, _, lines) in files.items():
            _write_lines(folder, name, lines)
        output = sim(language.tool, ['-S', '-r', str(language.run_tokens // 2)], list(files) + ['/'] + given_names,
                         folder)
        for run in parse_runs(output):
            against_given[run.a].append(run)
    given_set = {normal(line) for text in given for line in text.splitlines()}
    own = {}
    for name, (_, _, lines) in files.items():
        blank = given_lines(against_given[name], lines, given_set)
        own[name] = ['' if n in blank else line for n, line in enumerate(lines, 1)]
        _write_lines(folder, name, own[name])
    return own


def _side(files, own, name, first, last):
    """One side of a run, for the report: the file's path, the lines, which of them are given."""
    lines = files[name][2][first - 1:last]
    return {'path': files[name][1], 'first': first, 'lines': lines,
            'given': [n for n in range(len(lines)) if lines[n].strip() and not own[name][first - 1 + n].strip()]}


def _write_lines(folder, name, lines):
    path = os.path.join(folder, name)
    with open(path, 'w', encoding='utf-8') as stream:
        stream.write('\n'.join(lines) + '\n')
    os.chmod(path, 0o644)   # whatever the umask: the container's `student` reads it


def class_sources(submissions, package, scratch):
    """{Student: [(path, Language, text)]} of each submission (unpacked into scratch, as the grader
    unpacks it; the lab's package when it has one, else all of it), and [(name, reason)] of those
    that could not be read."""
    students, unread = {}, []
    for number, path in enumerate(submissions):
        who = student_of(path)
        unpacked = os.path.join(scratch, 'submission%d' % number)
        os.makedirs(unpacked)
        try:
            folder = unpack(path, unpacked)
        except (SubmissionError, OSError) as error:
            unread.append((who.name, str(error)))
            continue
        try:
            folder = os.path.join(folder, find_package(folder, package))
        except SubmissionError:
            pass   # no package, or two: the student's row says so; the code still counts
        students[who] = source_files(folder)
        shutil.rmtree(unpacked, ignore_errors=True)
    return students, unread


def compare_class(lab, package, submissions, image=None):
    """{'pairs': compare()'s, names as Student dicts, 'unread', 'error': a sentence or None,
    'given_files': how many given texts were removed, 'image': the image sim ran in (None: on this
    machine)}."""
    result = {'pairs': [], 'unread': [], 'error': None, 'given_files': 0, 'image': image}
    with tempfile.TemporaryDirectory(prefix='course-similarity-') as scratch:
        try:
            students, result['unread'] = class_sources(submissions, package, scratch)
            given = given_texts(lab)
            result['given_files'] = sum(map(len, given.values()))
            if lab not in GIVEN:
                raise SimilarityError('the material every student of %s is given is not listed (GIVEN in '
                                      'course_grader/similarity.py)' % lab)
            if not given:
                raise SimilarityError('what every student of %s is given was not found under %s (an install space '
                                      'without the course\'s sources?)' % (lab, repository_root()))
            compared = os.path.join(scratch, 'compared')
            os.makedirs(compared)
            os.chmod(compared, 0o755)   # mounted in the container (its parent, scratch, stays ours alone)
            result['pairs'] = compare(students, given, compared, in_container(image) if image else on_host)
        except SimilarityError as error:
            result['error'] = 'not compared: %s' % error
        except Exception as error:   # a fault of the comparison must not cost the class its grades
            result['error'] = 'the comparison failed: %r' % error
    for pair in result['pairs']:
        pair['a'], pair['b'] = pair['a']._asdict(), pair['b']._asdict()
    return result


def write_csv(pairs, path):
    """similarity.csv: a row per pair, names as grades.csv writes them (inert in a spreadsheet)."""
    with open(path, 'w', newline='', encoding='utf-8') as stream:
        writer = csv.writer(stream)
        writer.writerow(['student_a', 'id_a', 'student_b', 'id_b', 'percent', 'shared_lines'])
        for pair in pairs:
            writer.writerow([spreadsheet_cell(value) for value in (pair['a']['name'], pair['a']['id'], pair['b']['name'],
                                                       pair['b']['id'], pair['percent'], pair['shared_lines'])])


def write_class(lab, package, submissions, out, image=None):
    """Compares a class's submissions (compare_class: sim in a container of image, or on this
    machine without one); writes similarity.csv and what report.html's section shows
    (similarity.json) into out; returns a sentence for the terminal."""
    result = compare_class(lab, package, submissions, image)
    with open(os.path.join(out, RESULT_NAME), 'w', encoding='utf-8') as stream:
        json.dump(result, stream)
    write_csv(result['pairs'], os.path.join(out, CSV_NAME))
    if result['error']:
        return 'similar submissions: %s' % terminal_text(result['error'])
    return 'similar submissions: %d pair%s beyond the slides and the lab\'s pages (%s)%s' % (
        len(result['pairs']), '' if len(result['pairs']) == 1 else 's', os.path.join(out, CSV_NAME),
        '' if image else '; sim ran on this machine, not isolated')


def _who(student):
    return student['name'] + (' (%s)' % student['id'] if student['id'] else '')


def _side_html(side):
    """A run's side as a table cell: its file and lines, the given ones (taken out before comparing) grey."""
    shown = side['lines'][:SHOWN_LINES]
    given = set(side['given'])
    text = '\n'.join('<span style="color:#999">%s</span>' % html.escape(line) if n in given else html.escape(line)
                     for n, line in enumerate(shown))
    more = '\n… %d lines more' % (len(side['lines']) - len(shown)) if len(side['lines']) > len(shown) else ''
    return '<td><code>%s</code>, lines %d-%d<pre>%s%s</pre></td>' % (
        html.escape(side['path']), side['first'], side['first'] + len(side['lines']) - 1, text, more)


def html_section(out_dir):
    """report.html's section on similar submissions, from what write_class left in out_dir ('' when
    it did not run); every name and line of code escaped."""
    try:
        with open(os.path.join(out_dir, RESULT_NAME), encoding='utf-8') as stream:
            result = json.load(stream)
    except (OSError, ValueError):
        return ''
    esc = html.escape
    parts = ['<h2 id="similar-submissions">Similar submissions</h2>',
             '<p>Pairs of students whose code is alike beyond what the slides and the lab\'s pages give '
             'everyone (removed first: %d given files), by Debian\'s <code>sim_c++</code> (C++) and '
             '<code>sim_text</code> (Python); also in <code>%s</code>. Alike is not copied: read the lines (the given '
             'ones grey).</p>'
             % (result['given_files'], CSV_NAME)]
    if result['error']:
        parts.append('<p class="error">%s</p>' % esc(result['error']))
    elif not result['pairs']:
        parts.append('<p>No pair.</p>')
    else:
        parts.append('<div class="wide"><table><tr><th>student</th><th>student</th><th>alike</th><th>shared lines</th></tr>')
        for number, pair in enumerate(result['pairs']):
            parts.append('<tr><td>%s</td><td>%s</td><td class="num"><a href="#similar-%d">%d %%</a></td>'
                         '<td class="num">%d</td></tr>' % (esc(_who(pair['a'])), esc(_who(pair['b'])), number,
                                                          pair['percent'], pair['shared_lines']))
        parts.append('</table></div>')
        for number, pair in enumerate(result['pairs']):
            runs = pair['runs'][:SHOWN_RUNS]
            parts.append('<h3 id="similar-%d">%s and %s: %d %%, %d shared lines</h3>'
                         '<div class="wide"><table style="table-layout: fixed; width: 100%%">' % (
                number, esc(_who(pair['a'])), esc(_who(pair['b'])), pair['percent'], pair['shared_lines']))
            parts.append('<tr><th>%s</th><th>%s</th></tr>' % (esc(_who(pair['a'])), esc(_who(pair['b']))))
            for run in runs:
                parts.append('<tr>%s%s</tr>' % (_side_html(run['a']), _side_html(run['b'])))
            parts.append('</table></div>')
            if len(pair['runs']) > len(runs):
                parts.append('<p>%d runs more, not shown.</p>' % (len(pair['runs']) - len(runs)))
    for name, reason in result['unread']:
        parts.append('<p>Not compared: %s: %s</p>' % (esc(name), esc(reason)))
    return '\n'.join(parts)
