"""Sentences a student can act on, from their sources and from the logs of a run: the usual
mistakes of the course named (Python 2 prints, #! lines, execute bits, compiler errors, crashes)."""
import os
import re
import stat

# `print x` / `print 'x'` (a Python 2 print statement): `print` then something that is not an
# opening parenthesis, an operator or the end of the line.
_PY2_PRINT = re.compile(r'^\s*print(\s+[^\s(=.,)\]:]|\s*["\'])')
_COMPILER_ERROR = re.compile(r'^(?P<file>[^:\s][^:]*):(?P<line>\d+):(?:\d+:)?\s*(?:fatal )?error:\s*(?P<what>.*)$')
_CMAKE_ERROR = re.compile(r'^CMake Error at (?P<file>[^:]+):(?P<line>\d+)')


def python2_prints(path, display_name=None):
    """Sentences for every Python 2 print statement in a Python file (file, line, fix)."""
    display_name = display_name or os.path.basename(path)
    try:
        with open(path, errors='replace') as stream:
            lines = stream.read(1000000).splitlines()
    except OSError:
        return []
    found = []
    for number, line in enumerate(lines, 1):
        code = line.split('#', 1)[0].rstrip()
        if _PY2_PRINT.match(code):
            argument = code.strip()[len('print'):].strip()
            found.append('%s line %d: `%s` is Python 2; under Python 3 print is a function: '
                         'write `print(%s)`' % (display_name, number, code.strip(), argument))
    return found


def script_problems(path, display_name=None, python_commands=('python3',)):
    """What stops `rosrun PACKAGE script` from starting the script as the slide says: the execute
    bit (chmod +x) and the #! line. Empty when there is nothing to say."""
    display_name = display_name or os.path.basename(path)
    problems = []
    try:
        with open(path, 'rb') as stream:
            first = stream.readline(200).decode('utf-8', 'replace').rstrip('\r\n')
        mode = os.stat(path).st_mode
    except OSError as error:
        return ['%s cannot be read (%s)' % (display_name, error.strerror)]
    if not mode & stat.S_IXUSR:
        problems.append('%s is not executable: run `chmod +x %s` (rosrun only starts executable '
                        'scripts)' % (display_name, display_name))
    if not first.startswith('#!'):
        problems.append(_misplaced_shebang(path, display_name) or
                        '%s has no #! line: make its first line `#!/usr/bin/env python3`' % display_name)
    else:
        words = first[2:].split()
        interpreter = os.path.basename(words[-1] if words and words[0].endswith('/env') else
                                       (words[0] if words else ''))
        if interpreter not in python_commands:
            problems.append('%s line 1: `%s` asks for `%s`, which this course\'s ROS does not run '
                            '(it runs on Python 3): write `#!/usr/bin/env python3`'
                            % (display_name, first, interpreter or '(nothing)'))
    return problems


def _misplaced_shebang(path, display_name):
    """The sentence for a #! line a paste moved (indented, or below other lines), or None."""
    try:
        with open(path, 'rb') as stream:
            head = stream.read(4000).decode('utf-8', 'replace').splitlines()[:10]
    except OSError:
        return None
    for number, line in enumerate(head, 1):
        if line.lstrip().startswith('#!'):
            where = ('indented: `%s`' % line.rstrip() if number == 1 else
                     'on line %d, not line 1' % number)
            return ('%s: its #! line is %s. A paste from the slides moves it; it must be the first line '
                    'and start in column 1, or the shell runs the file instead of Python (`from: command '
                    'not found`)' % (display_name, where))
    return None


# What bash prints when it runs a Python file whose #! line is not the first one: `import` is
# ImageMagick's screenshot command on Debian, `from` no command at all.
_RUN_BY_THE_SHELL = re.compile(r'^(import(-im6\.q16)?: unable to open X server|.*: line \d+: from: command not found)',
                               re.M)


def first_compiler_error(build_log):
    """The first error of a catkin_make log, as one sentence, or None."""
    lines = build_log.splitlines()
    for number, line in enumerate(lines):
        match = _COMPILER_ERROR.match(line.strip())
        if match:
            sentence = 'first compiler error: %s line %s: %s' % (
                _short_path(match.group('file')), match.group('line'), match.group('what'))
            header = re.match(r'(\w+)/\w+\.h: No such file or directory', match.group('what'))
            if header:
                sentence += ('. The header comes from the package %s: add %s to find_package(catkin REQUIRED '
                             'COMPONENTS ...) in CMakeLists.txt and a <depend>%s</depend> to package.xml'
                             % ((header.group(1),) * 3))
            return sentence
        match = _CMAKE_ERROR.match(line.strip())
        if match:
            where = (_short_path(match.group('file')), match.group('line'))
            detail = []
            for following in lines[number + 1:]:
                if not following.strip():
                    if detail:
                        break
                    continue
                detail.append(following.strip())
            # The student's own line when the error is raised inside a CMake module.
            if where[0].startswith('/'):
                for following in lines[number + 1:number + 40]:
                    called = re.match(r'\s*(\S*CMakeLists\.txt):(\d+) ', following)
                    if called:
                        where = (_short_path(called.group(1)), called.group(2))
                        break
            text = ' '.join(detail).split(' with any of the following names')[0]
            return 'CMake error in %s line %s: %s' % (where + (text[:300],))
    return None


def _short_path(path):
    """src/<package>/... of a path inside the scratch workspace, for the student to recognize."""
    parts = path.split(os.sep)
    return os.sep.join(parts[parts.index('src') + 1:]) if 'src' in parts else path


def traceback_tail(output, lines=4):
    """The last lines of the last Python traceback in a program's output, or None."""
    text = output.splitlines()
    starts = [i for i, line in enumerate(text) if line.startswith('Traceback (most recent call last)')]
    if not starts:
        # A SyntaxError at start-up prints no 'Traceback' line in some cases: File ..., line N, ^
        match = [i for i, line in enumerate(text) if re.match(r'\s*\w*Error: ', line)]
        if not match:
            return None
        end = match[-1]
        return '\n'.join(text[max(0, end - lines + 1):end + 1])
    block = text[starts[-1]:]
    end = next((i for i, line in enumerate(block) if i and re.match(r'^\w[\w.]*(Error|Exception|Interrupt)\b', line)),
               len(block) - 1)
    return '\n'.join(block[max(1, end - lines + 1):end + 1])


def syntax_error(output):
    """(file, line, message) of a SyntaxError the interpreter reported at start-up, or None."""
    match = re.search(r'File "(?P<file>[^"]+)", line (?P<line>\d+)\n(?:.*\n){0,3}?\s*SyntaxError: (?P<what>.*)',
                      output)
    if not match:
        return None
    return os.path.basename(match.group('file')), int(match.group('line')), match.group('what').strip()


def explain_run(script, output, started, stopped_cleanly, python2_sentences=()):
    """Sentences about one run of a student's node: why it did not start, how it crashed, whether
    it stopped on Ctrl-C. python2_sentences: those of python2_prints for this script."""
    sentences = []
    error = syntax_error(output)
    if _RUN_BY_THE_SHELL.search(output):
        sentences.append('%s was run by the shell, not by Python (`%s`): make `#!/usr/bin/env python3` its '
                         'first line, starting in column 1' % (script, _RUN_BY_THE_SHELL.search(output).group(0)))
    elif error and 'print' in error[2].lower() and python2_sentences:
        sentences.append('%s does not start under Python 3: %s' % (script, python2_sentences[0]))
        if len(python2_sentences) > 1:
            sentences.append('%d more Python 2 prints in %s: lines %s' % (
                len(python2_sentences) - 1, script,
                ', '.join(re.search(r'line (\d+)', s).group(1) for s in python2_sentences[1:])))
    elif error:
        sentences.append('%s does not start: SyntaxError in %s line %d: %s' % ((script,) + error))
    else:
        tail = traceback_tail(output)
        if tail:
            sentences.append('%s crashed; its last traceback lines:\n%s' % (script, tail))
        elif not started:
            sentences.append('%s never started a ROS node (no init_node within the time limit)' % script)
    if stopped_cleanly is False:
        sentences.append('%s did not stop on Ctrl-C (SIGINT) and had to be killed: let '
                         'rospy.spin() or `while not rospy.is_shutdown()` end the program' % script)
    return sentences


def log_tail(path, lines=15):
    """The last lines of a log file (read from its last 200 kB), '' when it cannot be read."""
    try:
        with open(path, 'rb') as stream:
            stream.seek(0, os.SEEK_END)
            stream.seek(max(0, stream.tell() - 200000))
            return '\n'.join(stream.read().decode('utf-8', 'replace').splitlines()[-lines:])
    except OSError:
        return ''
