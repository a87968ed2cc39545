#!/usr/bin/env python3
"""CI, after the tests in an image: docs/student-docker.md, the page a student with Docker follows, run
as the student runs it.

The page's commands are read from its code blocks marked `<!-- student-docker-check: NAME -->` and
typed, as written, into shells on pseudo-terminals: the "laptop" is a bash in a fresh folder, the
container's shells are the page's `docker run -it` / `docker exec -it` / `docker start -ai` on those
terminals. It checks that the workspace is made in the mounted folder (its files the uid 1000's on
this Linux host), that a second and third terminal run the TurtleBot3 lab and its teleop with
nothing sourced (the robot moves), that the browser view shows a lab to the outside, that `exit`
stops the container and `docker start -ai` brings it back, that `docker cp` gets the logs out, the
page's two fixes (CR LF, lost executable bit), that a container killed in the middle of a
`catkin_make` keeps the workspace's sources and builds again, and that after `docker rm` a new
container finds the workspace built and sourced.

This engine has no bridge network (dockerd --bridge=none), where `-p` cannot publish a port: the
`docker` the page's commands call here is this script (--as-docker), which runs the real one with
`--network host` (the view and the master on free ports) in place of `-p`, the image under test in
place of the page's image name and a container name of its own in place of the page's; the view is
read on the machine's own address, as tools/docker-view-check.py reads it. The host needs only
python3 and docker (the helpers come from this tree's course_common and course_testing, which use
no ROS).

Usage: tools/student-docker-check.py IMAGE
"""
import hashlib
import importlib.util
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
import uuid

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [os.path.join(ROOT, 'src', 'course_common', 'src'), os.path.join(ROOT, 'src', 'course_testing', 'src')]
from course_common.processes import free_port  # noqa: E402  (after the path above)
from course_common.waiting import poll_until, wait_until  # noqa: E402
from course_testing.processes import ReadPtyProgram  # noqa: E402

PAGE = os.path.join(ROOT, 'docs', 'student-docker.md')
MARKED_BLOCK = re.compile(r'^<!-- student-docker-check: (\S+) -->\n```[^\n]*\n(.*?)^```', re.M | re.S)
STUDENT_UID = 1000          # the image's user `student` (docker/Dockerfile's STUDENT_UID)
VIEW_PORT_INSIDE = '8080'   # the port the image's view listens on in the container (-p ...:8080)
LAPTOP_PROMPT = 'laptop$ '
CONTAINER_PROMPT = 'student@'
SHORT, BUILD = 90, 600      # seconds: a command, a catkin_make on a busy machine
# `docker run` options that take a value, and those that do not (anything else on the page is unknown here).
RUN_VALUE_OPTIONS = {'-p', '--publish', '--name', '-v', '--volume', '-e', '--env', '-w', '--workdir', '--network'}
RUN_FLAGS = {'-i', '-t', '-it', '-ti', '--interactive', '--tty', '--rm', '-d', '--detach'}


def page_blocks(text):
    """{name: [command lines]} of the page's marked code blocks."""
    return {name: [line for line in body.splitlines() if line.strip()] for name, body in MARKED_BLOCK.findall(text)}


def engine_command(words, page_image, page_container, image, container, publish):
    """The arguments (after `docker`) of a page's docker command as this engine runs it."""
    command, rest = words[0], words[1:]
    if command == 'run':
        result, index = ['run'], 0
        while index < len(rest):
            word = rest[index]
            if word in ('-p', '--publish'):
                if not rest[index + 1].endswith(':' + VIEW_PORT_INSIDE):
                    raise SystemExit('student-docker-check: the page publishes %s, not the view\'s port %s'
                                     % (rest[index + 1], VIEW_PORT_INSIDE))
                result += publish
            elif word == '--name':
                result += ['--name', container if rest[index + 1] == page_container else rest[index + 1]]
            elif word in RUN_VALUE_OPTIONS:
                result += rest[index:index + 2]
            elif word in RUN_FLAGS:
                result.append(word)
                index += 1
                continue
            elif word.startswith('-'):
                raise SystemExit('student-docker-check: the page gives docker run %s, an option this check '
                                 'does not know' % word)
            else:   # the image, then the command in it
                return result + [image if word == page_image else word] + rest[index + 1:]
            index += 2
        raise SystemExit('student-docker-check: a docker run on the page names no image: %s' % ' '.join(words))
    if command in ('exec', 'start', 'rm', 'kill', 'stop'):
        return [command] + [container if word == page_container else word for word in rest]
    if command == 'cp':
        prefix = page_container + ':'
        return ['cp'] + [container + word[len(page_container):] if word.startswith(prefix) else word for word in rest]
    raise SystemExit('student-docker-check: the page runs docker %s, which this check does not know' % command)


def as_docker(arguments):
    """The `docker` the page's commands call on the check's terminals: the real one, on this engine."""
    setting = json.loads(os.environ['STUDENT_DOCKER_CHECK'])
    words = engine_command(arguments, setting['page_image'], setting['page_container'], setting['image'],
                           setting['container'], setting['publish'])
    os.execv(setting['docker'], [setting['docker']] + words)


def docker_words(line):
    """The words of a page's `docker ...` line (a shell would give these for the page's quoting)."""
    words = shlex.split(line)
    if words[0] != 'docker':
        raise SystemExit('student-docker-check: not a docker command: %s' % line)
    return words[1:]


def consistent(blocks):
    """One image name on the page, a Dockerfile that exists, and the Windows start lines the same
    docker run as the Linux one but for the folder's spelling. Returns (image name, container name)."""
    build = docker_words(blocks['build'][0])
    page_image = build[build.index('-t') + 1]
    dockerfile = os.path.join(ROOT, build[build.index('-f') + 1])
    if not os.path.isfile(dockerfile):
        raise SystemExit('student-docker-check: the page builds from %s, which does not exist' % dockerfile)
    start = docker_words(blocks['start'][-1])
    if start[-2] != page_image:
        raise SystemExit('student-docker-check: the page builds %s but starts %s' % (page_image, start[-2]))

    def without_folder(words):
        volume = words.index('-v') + 1
        return words[:volume] + [words[volume].split(':/home/student/', 1)[1]] + words[volume + 1:]
    for windows in ('start-powershell', 'start-cmd'):
        words = docker_words(blocks[windows][-1].replace('\\', '/'))
        if without_folder(words) != without_folder(start):
            raise SystemExit('student-docker-check: the page\'s %s is not the same docker run as its start:\n  %s\n  %s'
                             % (windows, blocks[windows][-1], blocks['start'][-1]))
    return page_image, start[start.index('--name') + 1]


class Terminal:
    """A terminal window on the laptop: a bash on a pseudo-terminal, where the page's lines are typed."""

    def __init__(self, name, env):
        self.name = name
        self.program = ReadPtyProgram(['bash', '--norc', '--noprofile'], env=env)
        self.commands = 0
        self.wait_for(re.escape(LAPTOP_PROMPT), 0, SHORT)

    def wait_for(self, pattern, mark, timeout):
        """The first match of the regular expression after output position `mark`."""
        try:
            return wait_until(lambda: re.search(pattern, self.program.output[mark:]), timeout,
                              what='%r in terminal %s' % (pattern, self.name))
        except AssertionError as error:
            raise SystemExit('student-docker-check: %s; the terminal showed:\n%s'
                             % (error, self.program.output[mark:][-3000:]))

    def run(self, line, timeout=SHORT, status=0):
        """Type a command that ends, then wait for it; its output (and its exit status when
        `status` is None; else it must be that)."""
        mark = len(self.program.output)
        self.commands += 1
        self.program.type('%s\necho "@@ $((%d)) $?"\n' % (line, self.commands))
        match = self.wait_for(r'@@ %d (\d+)' % self.commands, mark, timeout)
        output = self.program.output[mark:mark + match.start()]
        if status is not None and int(match.group(1)) != status:
            raise SystemExit('student-docker-check: `%s` in terminal %s ended with %s, not %d:\n%s'
                             % (line, self.name, match.group(1), status, output[-3000:]))
        return output if status is not None else (int(match.group(1)), output)

    def start(self, line, shows, timeout=SHORT):
        """Type a command that goes on (a container's shell, a roslaunch) and wait until it shows `shows`."""
        mark = len(self.program.output)
        self.program.type(line + '\n')
        self.wait_for(re.escape(shows), mark, timeout)
        return mark

    def interrupt(self):
        """Ctrl-C until the container's shell prompts again (a teleop reads the first one as its quit key,
        roslaunch the next as the signal)."""
        mark = len(self.program.output)
        for _ in range(3):
            self.program.type('\x03')
            if poll_until(lambda: CONTAINER_PROMPT in self.program.output[mark:], 20):
                return
        raise SystemExit('student-docker-check: Ctrl-C does not give terminal %s its prompt back:\n%s'
                         % (self.name, self.program.output[mark:][-3000:]))

    def leave(self):
        """`exit` in the container's shell, and the laptop's prompt back."""
        mark = len(self.program.output)
        self.program.type('exit\n')
        self.wait_for(re.escape(LAPTOP_PROMPT), mark, SHORT)

    def close(self):
        self.program.stop(timeout=1)


def files_digest(folder):
    """{path: sha256} of every file under folder."""
    digest = {}
    for directory, _, names in os.walk(folder):
        for name in names:
            with open(os.path.join(directory, name), 'rb') as data:
                digest[os.path.relpath(os.path.join(directory, name), folder)] = hashlib.sha256(data.read()).hexdigest()
    return digest


def give_to_student(path):
    """A file or folder the laptop's user made, as it is on a laptop whose user is uid 1000 (the
    page's case; this check runs as root or as that user)."""
    if os.getuid() != STUDENT_UID:
        os.chown(path, STUDENT_UID, STUDENT_UID)


def write_script(path, text, newline, mode):
    with open(path, 'w', newline=newline) as script:
        script.write(text)
    os.chmod(path, mode)
    give_to_student(path)


def docker_view_check():
    """tools/docker-view-check.py as a module: its in_image and its page reader are reused here."""
    spec = importlib.util.spec_from_file_location('docker_view_check',
                                                  os.path.join(ROOT, 'tools', 'docker-view-check.py'))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Laptop:
    """The student's laptop: a folder of their course work (the current directory of its terminals)
    and the `docker` of the page's commands, which runs them on this engine."""

    def __init__(self, image, blocks):
        self.image, self.blocks = image, blocks
        page_image, page_container = consistent(blocks)
        run = uuid.uuid4().hex[:8]
        self.container, self.reader = 'student-docker-check-' + run, 'student-docker-check-reader-' + run
        self.view_port, master_port = free_port(), free_port()
        self.folder = tempfile.mkdtemp(prefix='student-docker-check-')
        self.workspace = os.path.join(self.folder, 'catkin_ws')
        self.package = os.path.join(self.workspace, 'src', 'my_first_pkg')
        self.talker = os.path.join(self.package, 'scripts', 'talker.py')
        wrapper = os.path.join(self.folder, '.check-bin')
        os.mkdir(wrapper)
        with open(os.path.join(wrapper, 'docker'), 'w') as docker:
            docker.write('#!/bin/sh\nexec /usr/bin/python3 %s --as-docker "$@"\n'
                         % shlex.quote(os.path.abspath(__file__)))
        os.chmod(os.path.join(wrapper, 'docker'), 0o755)
        self.env = dict(os.environ, PATH=wrapper + ':/usr/bin:/bin:/usr/sbin:/sbin', PS1=LAPTOP_PROMPT, TERM='xterm',
                        STUDENT_DOCKER_CHECK=json.dumps({
                            'docker': shutil.which('docker'), 'image': image, 'container': self.container,
                            'page_image': page_image, 'page_container': page_container,
                            'publish': ['--network', 'host', '-e', 'COURSE_WEB_PORT=%d' % self.view_port,
                                        '-e', 'ROS_MASTER_URI=http://localhost:%d' % master_port]}))
        self.terminals = []
        self.started = time.monotonic()

    def terminal(self, name):
        """A new terminal window, in the course-work folder."""
        os.chdir(self.folder)
        self.terminals.append(Terminal(name, self.env))
        return self.terminals[-1]

    def passed(self, what):
        print('student-docker-check: %5.1f s  %s' % (time.monotonic() - self.started, what), flush=True)

    def close(self):
        for shell in self.terminals:
            shell.close()
        subprocess.run(['docker', 'rm', '-f', self.container, self.reader],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.chdir('/')
        shutil.rmtree(self.folder, ignore_errors=True)


def fail(what, output=''):
    raise SystemExit('student-docker-check: %s%s' % (what, ':\n' + output[-3000:] if output else ''))


def make_workspace(laptop, first):
    """Start: the folder, the container, the workspace made and built in it."""
    first.run(laptop.blocks['start'][0])
    give_to_student(laptop.workspace)
    first.start(laptop.blocks['start'][1], CONTAINER_PROMPT)
    for line in laptop.blocks['workspace']:
        first.run(line, timeout=BUILD)
    owner = os.stat(os.path.join(laptop.package, 'package.xml')).st_uid
    if owner != STUDENT_UID or not os.path.isfile(os.path.join(laptop.workspace, 'devel', 'setup.bash')):
        fail('the workspace is not built in the mounted folder as the student\'s (package.xml of uid %d)' % owner)
    laptop.passed('the workspace made and built in the mounted folder, its files uid %d\'s' % STUDENT_UID)


def drive_in_more_terminals(laptop):
    """The second and third terminal: the TurtleBot3 world and its teleop, nothing sourced; a fourth
    shell finds the student's package and sees the robot drive. Returns the second terminal."""
    second, third, fourth = laptop.terminal('2'), laptop.terminal('3'), laptop.terminal('4')
    second.start(laptop.blocks['second-terminal'][0], CONTAINER_PROMPT)
    second.start(laptop.blocks['second-terminal'][1], 'process[fake_tb3')
    third.start(laptop.blocks['third-terminal'][0], CONTAINER_PROMPT)
    mark = third.start(laptop.blocks['third-terminal'][1], 'Control Your TurtleBot3!')
    third.program.type('wwwww')
    third.wait_for(re.escape('linear vel 0.05'), mark, SHORT)
    fourth.start(laptop.blocks['second-terminal'][0], CONTAINER_PROMPT)
    found = fourth.run('rospack find my_first_pkg')
    if '/home/student/catkin_ws/src/my_first_pkg' not in found:
        fail('a new shell does not find the student\'s package', found)
    speed = fourth.run('rostopic echo -n 1 /odom/twist/twist/linear/x')
    if not float(re.search(r'-?\d+\.\d+', speed).group()) > 0.01:
        fail('the robot is not driving after w in the teleop', speed)
    third.program.type('s')
    third.interrupt()
    second.interrupt()
    laptop.passed('docker exec shells: the TurtleBot3 world, its teleop driving it, the student\'s package found')
    return second


def view_from_outside(laptop, first):
    """The page's lab in the first terminal, its view read from another container on the host's address."""
    view = docker_view_check()
    first.start(laptop.blocks['view'][0], 'process[')
    watched = view.in_image(laptop.image, laptop.reader, 'exec python3 tools/docker-view-check.py --watch %d'
                            % laptop.view_port, stdout=subprocess.PIPE, timeout=view.WAIT_SECONDS + 30)
    if watched.returncode != 0:
        fail('the view does not show the page\'s lab to the outside')
    first.interrupt()
    laptop.passed('the view, from outside: ' + watched.stdout.strip().replace('docker-view-check: ', ''))


def fix_a_script(laptop, first):
    """A script of the student's with CR LF, then without its executable bit: the page's errors, its fixes."""
    os.makedirs(os.path.dirname(laptop.talker), exist_ok=True)
    give_to_student(os.path.dirname(laptop.talker))
    write_script(laptop.talker, '#!/usr/bin/env python3\nprint("hello from my_first_pkg")\n', '\r\n', 0o755)
    for error, fix, spoil in (("env: 'python3\\r': No such file or directory", 'crlf-fix',
                               lambda: os.chmod(laptop.talker, 0o644)),
                              ("Couldn't find executable named talker.py", 'exec-fix', lambda: None)):
        status, output = first.run('rosrun my_first_pkg talker.py', status=None)
        if status == 0 or error not in output:
            fail('the script does not fail with %r as the page says' % error, output)
        first.run(laptop.blocks[fix][0])
        if 'hello from my_first_pkg' not in first.run('rosrun my_first_pkg talker.py'):
            fail('the page\'s %s does not mend the script' % fix)
        spoil()
    laptop.passed('the page\'s errors and fixes: CR LF (sed), the executable bit (chmod +x)')


def restart_and_copy_out(laptop, first, second):
    """`exit` stops the container and its docker exec shells; docker start -ai; docker cp of the logs."""
    mark = len(second.program.output)
    first.leave()
    second.wait_for(re.escape(LAPTOP_PROMPT), mark, SHORT)
    first.start(laptop.blocks['restart'][0], CONTAINER_PROMPT)
    if 'my_first_pkg' not in first.run('ls ~/catkin_ws/src'):
        fail('the restarted container lost the workspace')
    second.run(laptop.blocks['copy-out'][0])
    logs = [name for _, _, names in os.walk(os.path.join(laptop.folder, 'ros-logs')) for name in names]
    if not any(name.startswith('roslaunch-') for name in logs):
        fail('docker cp brought no roslaunch log out: %s' % logs[:10])
    laptop.passed('exit stopped the container and its docker exec shells; docker start -ai; docker cp (%d log files)'
                  % len(logs))


def kill_during_catkin_make(laptop, first):
    """docker kill while catkin_make runs cmake: the sources as they were, and it builds again."""
    sources = files_digest(os.path.join(laptop.workspace, 'src'))
    os.utime(os.path.join(laptop.package, 'CMakeLists.txt'))   # saved in the laptop's editor: cmake runs again
    mark = len(first.program.output)
    first.commands += 1
    first.program.type('%s\necho "@@ $((%d)) $?"\n' % (laptop.blocks['workspace'][-1], first.commands))
    first.wait_for(re.escape('-- Using CATKIN_DEVEL_PREFIX'), mark, BUILD)
    subprocess.run(['docker', 'kill', laptop.container], check=True, stdout=subprocess.DEVNULL)
    first.wait_for(re.escape(LAPTOP_PROMPT), mark, SHORT)
    if re.search(r'@@ %d ' % first.commands, first.program.output[mark:]):
        fail('catkin_make ended before docker kill: nothing was interrupted')
    if files_digest(os.path.join(laptop.workspace, 'src')) != sources:
        fail('the workspace\'s sources changed with the killed catkin_make')
    first.start(laptop.blocks['restart'][0], CONTAINER_PROMPT)
    first.run(laptop.blocks['workspace'][-1], timeout=BUILD)
    laptop.passed('docker kill during catkin_make: the sources as they were, catkin_make again builds')


def new_container(laptop, first):
    """A second docker run says the name is in use; docker rm, docker run: the workspace built and sourced."""
    first.leave()
    status, output = first.run(laptop.blocks['start'][1], status=None)
    if status == 0 or 'is already in use' not in output:
        fail('a second docker run does not say the name is in use', output)
    first.run(laptop.blocks['remove'][0])
    first.start(laptop.blocks['start'][1], CONTAINER_PROMPT)
    fifth = laptop.terminal('5')
    fifth.start(laptop.blocks['second-terminal'][0], CONTAINER_PROMPT)
    found = fifth.run('rospack find my_first_pkg && rosrun my_first_pkg talker.py')
    if 'hello from my_first_pkg' not in found:
        fail('the new container does not run the student\'s package', found)
    first.run(laptop.blocks['workspace'][-1], timeout=BUILD)
    laptop.passed('docker rm, a new container: the workspace there, sourced in a new shell; catkin_make builds')


def main(image):
    if os.getuid() not in (0, STUDENT_UID):
        fail('run it as root or as uid %d (the image\'s student)' % STUDENT_UID)
    with open(PAGE, encoding='utf-8') as page:
        laptop = Laptop(image, page_blocks(page.read()))
    try:
        first = laptop.terminal('1')
        make_workspace(laptop, first)
        second = drive_in_more_terminals(laptop)
        view_from_outside(laptop, first)
        fix_a_script(laptop, first)
        restart_and_copy_out(laptop, first, second)
        kill_during_catkin_make(laptop, first)
        new_container(laptop, first)
    finally:
        laptop.close()
    print('student-docker-check: docs/student-docker.md ran as written in %s (%.0f s)'
          % (image, time.monotonic() - laptop.started))


if __name__ == '__main__':
    if len(sys.argv) >= 2 and sys.argv[1] == '--as-docker':
        as_docker(sys.argv[2:])
    elif len(sys.argv) == 2:
        main(sys.argv[1])
    else:
        raise SystemExit(__doc__.strip().splitlines()[-1])
