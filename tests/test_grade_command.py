"""./grade.sh leaves no Docker engine behind: the dockerd it started goes when it ends, whatever the
grader's exit status; an engine that already ran stays.

Each case runs the real grade.sh and tools/docker.sh in a small folder of its own, with a
tools/setup.sh and tools/env.sh that install and build nothing, and stand-ins for docker, dockerd,
debootstrap and rosrun first on PATH (no engine is started, none is stopped)."""
import os
import shutil
import signal
import subprocess

import pytest

from course_common.process_table import command_line

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

STUBS = {
    # Answers while the dockerd stand-in whose pid file is in COURSE_DOCKER_ROOT runs.
    'docker': '''#!/bin/bash
case "$1" in
    version) kill -0 "$(cat "$COURSE_DOCKER_ROOT/dockerd.pid" 2>/dev/null)" 2>/dev/null; exit ;;
    import) cat > /dev/null ;;
    image) [ "$3" = -f ] && echo sha256:c0u75e ;;
esac
exit 0
''',
    # Writes its pid file as dockerd does, then waits to be stopped.
    'dockerd': '''#!/bin/bash
while [ $# -gt 0 ]; do [ "$1" = --pidfile ] && echo $$ > "$2"; shift; done
exec sleep 600
''',
    'debootstrap': '#!/bin/bash\nexit 0\n',
    # The grader: says whether an engine answered while it graded, and exits with GRADER_STATUS.
    'rosrun': '''#!/bin/bash
docker version && echo "engine up, image $COURSE_GRADER_IMAGE" > "$COURSE_DOCKER_ROOT/grader.txt"
exit "${GRADER_STATUS:-0}"
''',
}


@pytest.fixture
def checkout(tmp_path):
    """grade.sh and tools/docker.sh as in the repository; the rest stand-ins."""
    top = tmp_path / 'checkout'
    (top / 'tools').mkdir(parents=True)
    shutil.copy2(os.path.join(ROOT, 'grade.sh'), str(top / 'grade.sh'))
    shutil.copy2(os.path.join(ROOT, 'tools', 'docker.sh'), str(top / 'tools' / 'docker.sh'))
    (top / 'tools' / 'setup.sh').write_text('#!/bin/bash\nexit 0\n')
    (top / 'tools' / 'setup.sh').chmod(0o755)
    (top / 'tools' / 'env.sh').write_text('# nothing to source\n')
    stubs = tmp_path / 'bin'
    stubs.mkdir()
    for name, text in STUBS.items():
        (stubs / name).write_text(text)
        (stubs / name).chmod(0o755)
    (tmp_path / 'docker').mkdir()
    return top


def run_grade(top, **env):
    base = {'PATH': '%s:/usr/bin:/bin' % (top.parent / 'bin'), 'HOME': str(top.parent),
            'COURSE_DOCKER_ROOT': str(top.parent / 'docker')}
    return subprocess.run([str(top / 'grade.sh'), 'my_turtle', 'alice/', '--out', 'grades'],
                          env=dict(base, **env), cwd=str(top.parent), stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=120)


def dockerd_pid(top):
    return int((top.parent / 'docker' / 'dockerd.pid').read_text())


def running(pid):
    return command_line(pid) == '%d sleep 600' % pid


@pytest.mark.parametrize('status', [0, 2])
def test_the_dockerd_grade_sh_started_is_stopped_when_it_ends(checkout, status):
    result = run_grade(checkout, GRADER_STATUS=str(status))
    pid = dockerd_pid(checkout)
    try:
        assert result.returncode == status, result.stdout
        assert 'docker: starting dockerd (overlay2' in result.stdout
        assert (checkout.parent / 'docker' / 'grader.txt').read_text() == 'engine up, image sha256:c0u75e\n'
        assert not running(pid), 'grade.sh left its dockerd (%d) running' % pid
    finally:
        if running(pid):
            os.kill(pid, signal.SIGKILL)


def test_an_engine_that_already_answered_is_left_running(checkout):
    root = checkout.parent / 'docker'
    engine = subprocess.Popen([str(checkout.parent / 'bin' / 'dockerd'), '--pidfile', str(root / 'dockerd.pid')])
    try:
        while not (root / 'dockerd.pid').exists():   # the stand-in writes it first thing
            assert engine.poll() is None
        result = run_grade(checkout, DOCKER_HOST='unix://%s/docker.sock' % root)
        assert result.returncode == 0, result.stdout
        assert 'starting dockerd' not in result.stdout
        assert (root / 'grader.txt').read_text() == 'engine up, image sha256:c0u75e\n'
        assert running(engine.pid)
    finally:
        engine.kill()
        engine.wait()
