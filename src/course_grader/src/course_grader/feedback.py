"""Sentences a student can act on, from their sources and from the logs of a run: the usual
mistakes of the course named (Python 2 prints, #! lines, execute bits, compiler errors, crashes),
each one a paste of the slides makes with the section of docs/copying-the-slides/ that explains it."""
import os
import re
import shutil
import signal
import stat

# The section of docs/copying-the-slides/ that explains each mistake a paste of a lab's slides makes
# ({package: {mistake: page#anchor}}, the anchor GitHub gives the section's heading; test_feedback
# checks that each is one of its page's).
COPYING_FOLDER = 'docs/copying-the-slides/'
COPYING_SECTIONS = {
    'move_turtlebot3': {
        'shebang_moved': 'move_turtlebot3.md#1-the-whole-paste-indented',
        'cut_string': 'move_turtlebot3.md#2-a-string-cut-at-the-end-of-a-line',
        'lost_underscores': 'move_turtlebot3.md#3-lost-underscores',
        'indentation': 'move_turtlebot3.md#4-indentationerror',
        'msq': 'move_turtlebot3.md#5-msq-for-msg',
        'python': 'move_turtlebot3.md#python3-not-python-in-the-first-line',
        'chmod': 'move_turtlebot3.md#chmod-x',
        'python2_print': 'move_turtlebot3.md#python-2-prints',
        'publisher_first': 'move_turtlebot3.md#avoid_obstaclepy-the-publisher',
    },
    'my_turtle': {
        'missing_header': 'my_turtle.md#turtlesimposeh-no-such-file-or-directory',
        'undeclared_velocity': 'my_turtle.md#lin_vel_-was-not-declared',
        'roscppreset': 'my_turtle.md#what-a-paste-from-the-slides-does-first',
    },
    'ros_exercises': {
        'missing_header': 'my_turtle.md#turtlesimposeh-no-such-file-or-directory',
        'fig5': 'ros_exercises.md#what-a-paste-of-fig-5-does-first',
    },
}
# What goes wrong with a package in a folder that Docker mounts from Windows or macOS.
DOCKER_SECTIONS = {
    'line_endings': 'docs/student-docker.md#windows-line-endings',
    'executable_bits': 'docs/student-docker.md#lost-executable-bits',
}


def copying_section(package, mistake):
    """docs/copying-the-slides/PAGE#ANCHOR of a mistake a paste of the package's slides makes, or None."""
    section = COPYING_SECTIONS.get(package, {}).get(mistake)
    return COPYING_FOLDER + section if section else None


def _see(package, mistake):
    section = copying_section(package, mistake)
    return ' (see %s)' % section if section else ''


# `print x` / `print 'x'` (a Python 2 print statement): `print` then something that is not an
# opening parenthesis, an operator or the end of the line.
_PY2_PRINT = re.compile(r'^\s*print(\s+[^\s(=.,)\]:]|\s*["\'])')
_COMPILER_ERROR = re.compile(r'^(?P<file>[^:\s][^:]*):(?P<line>\d+):(?:\d+:)?\s*(?:fatal )?error:\s*(?P<what>.*)$')
_CMAKE_ERROR = re.compile(r'^CMake Error at (?P<file>[^:]+):(?P<line>\d+)')
# The names with underscores in the slides' Python, as a paste from the PDF gives them (a space for
# each `_`), and as they should be.
_LOST_UNDERSCORES = [(re.compile(pattern), meant) for pattern, meant in (
    (r'\bsensor msgs\b', 'sensor_msgs'), (r'\bgeometry msgs\b', 'geometry_msgs'), (r'\bstd msgs\b', 'std_msgs'),
    (r'\binit node\b', 'init_node'), (r'\bis shutdown\b', 'is_shutdown'), (r'\bqueue size\b', 'queue_size'),
    (r"\bif name == ' main ':", "if __name__ == '__main__':"), (r"'/?cmd vel'", "'cmd_vel'"),
    (r"'vel publisher'", "'vel_publisher'"), (r"'obstacle avoidance'", "'obstacle_avoidance'"),
    (r"'laser data'", "'laser_data'"))]


def _read_lines(path, limit=1000000):
    try:
        with open(path, errors='replace') as stream:
            return stream.read(limit).splitlines()
    except OSError:
        return []


def python2_prints(path, display_name=None):
    """Sentences for every Python 2 print statement in a Python file (file, line, fix)."""
    display_name = display_name or os.path.basename(path)
    found = []
    for number, line in enumerate(_read_lines(path), 1):
        code = line.split('#', 1)[0].rstrip()
        if _PY2_PRINT.match(code):
            argument = code.strip()[len('print'):].strip()
            found.append('%s line %d: `%s` is Python 2; under Python 3 print is a function: '
                         'write `print(%s)`' % (display_name, number, code.strip(), argument))
    return found


def script_problems(path, display_name=None, python_commands=('python3',), package=None):
    """What stops `rosrun PACKAGE script` from starting the script as the slide says: the execute
    bit (chmod +x), the #! line and Windows line endings. Empty when there is nothing to say.
    package: whose copying page the sentences name."""
    display_name = display_name or os.path.basename(path)
    problems = []
    try:
        with open(path, 'rb') as stream:
            raw = stream.readline(200)
        mode = os.stat(path).st_mode
    except OSError as error:
        return ['%s cannot be read (%s)' % (display_name, error.strerror)]
    first = raw.decode('utf-8', 'replace').rstrip('\r\n')
    if not mode & stat.S_IXUSR:
        chmod = copying_section(package, 'chmod')
        problems.append('%s is not executable: run `chmod +x %s` (rosrun only starts executable scripts%s; a '
                        'folder that Docker mounts from Windows or macOS can lose the bit: see %s)'
                        % (display_name, display_name, ': see %s' % chmod if chmod else '',
                           DOCKER_SECTIONS['executable_bits']))
    if not first.startswith('#!'):
        problems.append(_misplaced_shebang(path, display_name, package) or
                        '%s has no #! line: make its first line `#!/usr/bin/env python3`' % display_name)
    else:
        words = first[2:].split()
        through_env = bool(words) and words[0].endswith('/env')
        command = words[-1] if through_env else (words[0] if words else '')
        interpreter = os.path.basename(command)
        if raw.endswith(b'\r\n'):
            said = ("`env: '%s\\r': No such file or directory`" % interpreter if through_env else
                    '`%s^M: bad interpreter`' % command)
            problems.append('%s has Windows line endings (CRLF): rosrun stops at its #! line with %s; convert the '
                            'file with `sed -i \'s/\\r$//\' %s` (see %s)'
                            % (display_name, said, display_name, DOCKER_SECTIONS['line_endings']))
        if interpreter not in python_commands:
            problems.append(_interpreter_sentence(display_name, first, command, interpreter, python_commands,
                                                  package))
    return problems


def _interpreter_sentence(display_name, first, command, interpreter, python_commands, package):
    """Why a #! line that names another interpreter than the rubric's (`python`, say) costs the point."""
    found = shutil.which(command) if command else None
    wanted = '#!/usr/bin/env %s' % python_commands[0]
    if not found:
        return ('%s line 1: `%s` asks for `%s`, which this machine does not have (rosrun says '
                '`env: \'%s\': No such file or directory`): write `%s`%s'
                % (display_name, first, interpreter or '(nothing)', interpreter, wanted, _see(package, 'python')))
    here = os.path.basename(os.path.realpath(found))
    runs = (' it runs here (`%s` is Python 3 on this machine), but' % interpreter
            if here.startswith('python3') and interpreter != here else '')
    return ('%s line 1: `%s` asks for `%s`, not `%s`:%s the lab\'s rubric gives this point only to a #! '
            'line that names %s: write `%s`%s' % (display_name, first, interpreter, python_commands[0], runs,
                                                   ' or '.join('`%s`' % c for c in python_commands), wanted,
                                                   _see(package, 'python')))


def _misplaced_shebang(path, display_name, package=None):
    """The sentence for a #! line a paste moved (indented, or below other lines), or None."""
    moved = _shebang_place(_read_lines(path, 4000))
    if not moved:
        return None
    where = 'indented: `%s`' % moved[1] if moved[0] == 1 else 'on line %d, not line 1' % moved[0]
    return ('%s: its #! line is %s. A paste from the slides moves it; it must be the first line and start in '
            'column 1, or bash runs the file instead of Python (`import: unable to open X server`, `from: command '
            'not found`)%s' % (display_name, where, _see(package, 'shebang_moved')))


# What bash prints when it runs a Python file whose #! line is not the first one: `import` is
# ImageMagick's screenshot command on Debian, `from` no command at all.
_RUN_BY_THE_SHELL = re.compile(r'^(import(-im6\.q16)?: unable to open X server|.*: line \d+: from: command not found)',
                               re.M)
# What env prints for a #! line that ends in a carriage return (a file saved with Windows line endings):
# bookworm's coreutils names itself as the #! line calls it (`/usr/bin/env:`, `/bin/env:`), trixie's `env:`.
_CRLF_SHEBANG = re.compile(r"^(?:\S*/)?env: \S?(\S+?)(\\r|\r)\S?: No such file or directory", re.M)
# Compiler and CMake errors a paste of the slides makes, and the mistake behind each (COPYING_SECTIONS).
_PASTE_BUILD_ERRORS = (
    (re.compile(r'^\w+/\w+\.h: No such file or directory'), 'missing_header'),
    (re.compile(r"^.(lin|ang)_vel_. was not declared"), 'undeclared_velocity'),
    (re.compile(r'^#include expects|geonetry_msgs|ltnear|^.Spin. is not a member of .ros.|^.turtlesim. does not name'),
     'fig5'),
    (re.compile(r'provided by "roscppreset"'), 'roscppreset'),
)


def first_compiler_error(build_log):
    """The first error of a catkin_make log, as one sentence, or None. The package is the one the
    error is in: its copying page is named when a paste of the slides makes such an error."""
    lines = build_log.splitlines()
    for number, line in enumerate(lines):
        match = _COMPILER_ERROR.match(line.strip())
        if match:
            where = _short_path(match.group('file'))
            sentence = 'first compiler error: %s line %s: %s' % (where, match.group('line'), match.group('what'))
            header = re.match(r'(\w+)/\w+\.h: No such file or directory', match.group('what'))
            if header:
                sentence += ('. The header comes from the package %s: add %s to find_package(catkin REQUIRED '
                             'COMPONENTS ...) in CMakeLists.txt and a <depend>%s</depend> to package.xml'
                             % ((header.group(1),) * 3))
            return sentence + _paste_build_error(where, match.group('what'))
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
            return ('CMake error in %s line %s: %s' % (where + (text[:300],))) + _paste_build_error(where[0], text)
    return None


def _paste_build_error(where, what):
    """' (see docs/copying-the-slides/...)' for a build error a paste of the slides makes, or ''."""
    package = where.split(os.sep)[0]
    for pattern, mistake in _PASTE_BUILD_ERRORS:
        if pattern.search(what):
            return _see(package, mistake)
    return ''


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
    """(file, line, kind, message) of a SyntaxError (IndentationError, TabError) the interpreter
    reported at start-up, or None."""
    match = re.search(r'File "(?P<file>[^"]+)", line (?P<line>\d+)\n(?:.*\n){0,3}?\s*'
                      r'(?P<kind>SyntaxError|IndentationError|TabError): (?P<what>.*)', output)
    if not match:
        return None
    return (os.path.basename(match.group('file')), int(match.group('line')), match.group('kind'),
            match.group('what').strip())


def _shebang_place(lines):
    """(line number, line) of a #! line a paste moved (indented, or below line 1) in the first ten
    lines, or None."""
    for number, line in enumerate(lines[:10], 1):
        if line.lstrip().startswith('#!'):
            return None if number == 1 and line.startswith('#!') else (number, line.rstrip())
    return None


def _lost_underscores(lines):
    """['`geometry msgs` for `geometry_msgs`', ...]: the slides' names a paste wrote with spaces."""
    found = []
    for pattern, meant in _LOST_UNDERSCORES:
        for line in lines:
            match = pattern.search(line.split('#', 1)[0])
            if match:
                found.append('`%s` for `%s`' % (match.group(0), meant))
                break
    return found


def _start_error(script, error, lines, package, python2_sentences):
    """Sentences for a script Python did not start: error is syntax_error's."""
    _, number, kind, what = error
    text = lines[number - 1].strip() if 0 < number <= len(lines) else ''
    seen = '%s does not start: line %d%s: `%s: %s`' % (script, number, ', `%s`' % text if text else '', kind, what)
    lost = _lost_underscores([text])
    if kind == 'SyntaxError' and 'print' in what.lower() and python2_sentences:
        sentences = ['%s does not start under Python 3: %s%s' % (script, python2_sentences[0],
                                                                 _see(package, 'python2_print'))]
        if len(python2_sentences) > 1:
            sentences.append('%d more Python 2 prints in %s: lines %s' % (
                len(python2_sentences) - 1, script,
                ', '.join(re.search(r'line (\d+)', s).group(1) for s in python2_sentences[1:])))
        return sentences
    if 'unterminated string' in what or 'EOL while scanning' in what:
        return ['%s. A string is cut at the end of the line (a paste keeps only what the slide\'s box shows): '
                'end it on the same line%s' % (seen, _see(package, 'cut_string'))]
    if lost:
        every = _lost_underscores(lines)
        return ['%s. The paste lost the underscores, a space for each `_`: %s: put every underscore back%s'
                % (seen, ', '.join(every), _see(package, 'lost_underscores'))]
    if kind in ('IndentationError', 'TabError'):
        return ['%s. The paste starts the lines of one block at different columns: indent 4 spaces per level, '
                'every line of a block at the same column%s' % (seen, _see(package, 'indentation'))]
    return ['%s does not start: %s in %s line %d: %s' % (script, kind, error[0], number, what)]


# A node name or topic in quotes that lost its underscore: what the master answers rospy.
_ILLEGAL_NAME = re.compile(r'unable to register \w+ \[(?P<name>[^\]]*)\] with master: .*contains illegal chars')


def _crash(script, output, lines, package):
    """The sentence for a node that crashed (a traceback, or rospy's FATAL), or None."""
    illegal = _ILLEGAL_NAME.search(output)
    if illegal:
        return ('%s does not start a node: ROS refuses the name `%s` (`contains illegal chars`): a name in quotes '
                'lost its underscore in the paste (a space for each `_`): put every underscore back%s'
                % (script, illegal.group('name'), _see(package, 'lost_underscores')))
    tail = traceback_tail(output)
    if not tail:
        return None
    where = re.findall(r'File "[^"]*%s", line (\d+)' % re.escape(os.path.basename(script)), tail)
    at = ' line %s' % where[-1] if where else ''
    undefined = re.search(r"^NameError: name '(\w+)' is not defined", tail, re.M)
    misspelt = next((line.strip() for line in lines if re.search(r'\bmsq\b', line)), None)
    if undefined and undefined.group(1) == 'msg' and misspelt and copying_section(package, 'msq'):
        return ("%s fails in its callback,%s: `NameError: name 'msg' is not defined`, at every scan: the paste "
                "wrote `msq` for `msg` (`%s`): write `msg` everywhere%s" % (script, at, misspelt, _see(package, 'msq')))
    if undefined and undefined.group(1) in ('pub', 'move') and copying_section(package, 'publisher_first'):
        return ("%s fails in its callback,%s: `NameError: name '%s' is not defined`: a scan came before the "
                "line that makes `%s`: make `pub` and `move` before the `rospy.Subscriber` line%s"
                % (script, at, undefined.group(1), undefined.group(1), _see(package, 'publisher_first')))
    return '%s crashed; its last traceback lines:\n%s' % (script, tail)


def explain_run(script, output, started, stopped_cleanly, python2_sentences=(), path=None, package=None,
                exit_before_stop=None):
    """Sentences about one run of a student's node: why it did not start, how it crashed, whether
    it stopped on Ctrl-C. python2_sentences: those of python2_prints for this script; path: the
    script (its lines explain a paste's errors); package: whose copying page the sentences name;
    exit_before_stop: its exit status (Popen's) when it ended before the grader stopped it."""
    sentences = []
    killed = exit_before_stop == -signal.SIGKILL
    lines = _read_lines(path) if path else []
    error = syntax_error(output)
    shell = _RUN_BY_THE_SHELL.search(output)
    moved = _shebang_place(lines)
    crlf = _CRLF_SHEBANG.search(output)
    if crlf:
        sentences.append('%s does not start: `%s`: the file has Windows line endings (CRLF), and its #! line '
                         'asks for `%s` and a carriage return; convert the file with `sed -i \'s/\\r$//\' %s` '
                         '(see %s)' % (script, crlf.group(0), crlf.group(1), script, DOCKER_SECTIONS['line_endings']))
    elif shell or (error and moved):
        how = ('was run by the shell, not by Python (`%s`)' % shell.group(0) if shell else
               'does not start: Python stops at line %d with `%s: %s`, and rosrun has bash run it (`import: unable '
               'to open X server`, `from: command not found`)' % (error[1], error[2], error[3]))
        place = ('its #! line is %s' % ('indented: `%s`' % moved[1] if moved[0] == 1 else 'on line %d' % moved[0])
                 if moved else 'its #! line is not the first line')
        sentences.append('%s %s: %s (a paste from the slides moves it): make `#!/usr/bin/env python3` its first '
                         'line, starting in column 1, and move every line left by the paste\'s indentation%s'
                         % (script, how, place, _see(package, 'shebang_moved')))
    elif error:
        sentences += _start_error(script, error, lines, package, python2_sentences)
    else:
        crash = _crash(script, output, lines, package)
        if crash:
            sentences.append(crash)
        elif killed:
            # Nothing of the grader's kills a node during its run: the kernel does when memory runs
            # out, and takes the student's processes first (grading_session.OOM_KILLED_FIRST).
            sentences.append('%s was killed (SIGKILL) %s, not by the grader: the kernel does this when memory '
                             'runs out. Does it keep everything it receives, or start processes without end?'
                             % (script, 'during the run' if started else 'before it started a ROS node'))
        elif not started:
            sentences.append('%s never started a ROS node (no init_node within the time limit)' % script)
    if stopped_cleanly is False:
        sentences.append('%s did not stop on Ctrl-C (SIGINT) and had to be killed: let '
                         'rospy.spin() or `while not rospy.is_shutdown()` end the program' % script)
    return sentences


# What a program built from a paste of the slides prints when it runs (C++), and the mistake behind each.
_PASTE_RUN_ERRORS = (
    (re.compile(r'You must call ros::init\(\) before creating the first NodeHandle'), 'fig5',
     'a node stopped at once: `You must call ros::init() before creating the first NodeHandle` (Fig. 5 has no '
     '`ros::init`): make `ros::init(argc, argv, "NAME");` the first line of its main'),
    (re.compile(r'Turtle subscriber@\('), 'fig5',
     'its lines say `Turtle subscriber@(...]`, Fig. 5\'s `(` for `[`: print `"Turtle subscriber@[%f, %f, %f]"`'),
)


def paste_run_error(package, output):
    """The sentence for what a program built from a paste of the package's slides printed, when a
    paste makes it print that (with its section of docs/copying-the-slides/), or None."""
    for pattern, mistake, sentence in _PASTE_RUN_ERRORS:
        if copying_section(package, mistake) and pattern.search(output):
            return sentence + _see(package, mistake)
    return None


def log_tail(path, lines=15):
    """The last lines of a log file (read from its last 200 kB), '' when it cannot be read."""
    try:
        with open(path, 'rb') as stream:
            stream.seek(0, os.SEEK_END)
            stream.seek(max(0, stream.tell() - 200000))
            return '\n'.join(stream.read().decode('utf-8', 'replace').splitlines()[-lines:])
    except OSError:
        return ''
