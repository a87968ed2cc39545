#!/usr/bin/env python3
"""The grading image against the students' image, side by side in one run: each one's size, its size
compressed, and the time a GitHub Classroom runner takes from `docker pull` to the first criterion of
a move_turtlebot3 grading, printed as a Markdown table.

    source tools/env.sh && /usr/bin/python3 bench/grading_image_bench.py [--suite bookworm] [--runs 1]

Run as root (it starts a dockerd of its own), with the course's engine answering (tools/docker.sh,
`course_docker_engine`; DOCKER_HOST set as it sets it). It builds ros-course:SUITE and
ros-course-grader:SUITE first (tools/docker.sh; cached when nothing changed; --no-build skips it).

- size: what `docker image inspect` says (uncompressed, every layer);
- compressed: the bytes of `docker save IMAGE | gzip -1` (about what a registry stores and a pull
  downloads);
- pull: the Classroom workflow's step *Course image* (`docker pull` of the image, which is not there)
  from a registry on this machine: Debian's `docker-registry` (install it: apt-get install
  docker-registry), started here on a free port of 127.0.0.1 with its storage in a temporary folder,
  stopped by its PID at the end. So that the pull is honest (no layer already there, the two images
  sharing their first layers), it pulls into a second, empty dockerd started here (its own data root
  in a temporary folder, stopped by its PID), emptied again between two pulls (every image removed,
  checked: no image and no layer left in its data root);
- first criterion: then the workflow's step *Grade* (the `docker run` of the grading, as
  `classroom_template` writes it) of the move_turtlebot3 model, until the first criterion's line
  (`PASS`, `FAIL`) comes out: `grade_platform` prints the criteria when the grading ends, so this is
  the whole grading; the table gives the pull, the grading and their sum.

A runner downloads from a registry over the network: add the compressed size at the runner's
bandwidth (about 1 s per 100 MB at the 1 Gbit/s GitHub's hosted runners often reach) to the pull.
docs/benchmarks.md, "The grading image", has the figures and the target.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

import yaml

from course_common.processes import free_port, stop_process_group
from course_common.waiting import poll_until

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV_SH = os.path.join(ROOT, 'tools', 'env.sh')
DOCKER_SH = os.path.join(ROOT, 'tools', 'docker.sh')
LAB = 'move_turtlebot3'
MODEL = os.path.join(ROOT, 'src', LAB)
CRITERION = re.compile(r'^(PASS|FAIL|----) ')


def sh(command, env=None, **kwargs):
    return subprocess.run(command, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          universal_newlines=True, check=True, **kwargs).stdout


def build(suite):
    """The two images' names, built (or found in the build cache) by tools/docker.sh."""
    names = sh(['bash', '-c', 'source "$0" && course_docker_engine && course_docker_image "$1" && '
                'course_docker_grading_image "$1"', DOCKER_SH, suite]).split()
    return names[-2], names[-1]


def compressed_bytes(image):
    """The bytes of `docker save IMAGE | gzip -1`."""
    save = subprocess.Popen(['docker', 'save', image], stdout=subprocess.PIPE, stdin=subprocess.DEVNULL)
    gzip = subprocess.Popen(['gzip', '-1'], stdin=save.stdout, stdout=subprocess.PIPE)
    save.stdout.close()
    total = 0
    while True:
        chunk = gzip.stdout.read(1 << 20)
        if not chunk:
            break
        total += len(chunk)
    if gzip.wait() or save.wait():
        raise SystemExit('docker save %s | gzip -1 failed' % image)
    return total


def wait_for(what, ready, process, seconds=60):
    if not poll_until(lambda: process.poll() is not None or ready(), seconds, poll=0.2):
        raise SystemExit('%s did not answer within %d s' % (what, seconds))
    if process.poll() is not None:
        raise SystemExit('%s ended (exit %d) before it answered' % (what, process.returncode))


def start_registry(folder):
    """Debian's docker-registry serving on a free port of 127.0.0.1, storing in `folder`:
    (process, 'localhost:PORT')."""
    if not shutil.which('docker-registry'):
        raise SystemExit('docker-registry is not installed: apt-get install docker-registry')
    port = free_port()
    config = os.path.join(folder, 'registry.yml')
    with open(config, 'w') as stream:
        yaml.safe_dump({'version': 0.1, 'log': {'level': 'warn'},
                        'storage': {'filesystem': {'rootdirectory': os.path.join(folder, 'storage')},
                                    'delete': {'enabled': True}},
                        'http': {'addr': '127.0.0.1:%d' % port}}, stream)
    log = open(os.path.join(folder, 'registry.log'), 'w')
    process = subprocess.Popen(['docker-registry', 'serve', config], stdout=log, stderr=subprocess.STDOUT,
                               stdin=subprocess.DEVNULL, start_new_session=True)

    def answers():
        try:
            return urllib.request.urlopen('http://127.0.0.1:%d/v2/' % port, timeout=1).status == 200
        except OSError:
            return False
    wait_for('docker-registry', answers, process)
    return process, 'localhost:%d' % port


def start_engine(folder):
    """A second dockerd, empty, its data in `folder`: (process, its DOCKER_HOST)."""
    host = 'unix://%s/docker.sock' % folder
    log = open(os.path.join(folder, 'dockerd.log'), 'w')
    process = subprocess.Popen(
        ['dockerd', '--data-root', os.path.join(folder, 'data'), '--exec-root', os.path.join(folder, 'exec'),
         '--pidfile', os.path.join(folder, 'dockerd.pid'), '--host', host, '--storage-driver', 'overlay2',
         '--iptables=false', '--ip-masq=false', '--bridge=none'],
        stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True)
    env = dict(os.environ, DOCKER_HOST=host)
    wait_for('the second dockerd', lambda: subprocess.run(['docker', 'version'], env=env, stdout=subprocess.DEVNULL,
                                                          stderr=subprocess.DEVNULL).returncode == 0, process)
    return process, env


def empty_engine(env, folder):
    """Every image of the second engine removed; checked: none listed, no layer in its data root."""
    images = sh(['docker', 'image', 'ls', '-aq'], env).split()
    if images:
        subprocess.run(['docker', 'rmi', '-f'] + images, env=env, stdout=subprocess.DEVNULL, check=True)
    sh(['docker', 'image', 'prune', '-af'], env)
    left = sh(['docker', 'image', 'ls', '-aq'], env).split()
    layers = [name for name in os.listdir(os.path.join(folder, 'data', 'overlay2')) if name != 'l'] \
        if os.path.isdir(os.path.join(folder, 'data', 'overlay2')) else []
    if left or layers:
        raise SystemExit('the second engine still has %d images and %d layers' % (len(left), len(layers)))


def workflow_steps(image, folder):
    """The Classroom workflow of the lab for `image`, as classroom_template writes it: (job env, steps)."""
    template = os.path.join(folder, 'template')
    sh(['bash', '-c', 'source "$0" && exec "$@"', ENV_SH, 'rosrun', 'course_grader', 'classroom_template', LAB,
        template, '--image', image])
    with open(os.path.join(template, '.github', 'workflows', 'classroom.yml')) as stream:
        (job,) = yaml.safe_load(stream)['jobs'].values()
    return {key: str(value) for key, value in job['env'].items()}, {step['name']: step for step in job['steps']}


def classroom_run(image, env, folder):
    """The steps Course image and Grade of a push of the model: (pull s, grading s to the first
    criterion, the total line)."""
    job_env, steps = workflow_steps(image, folder)
    workspace = os.path.join(folder, 'workspace')
    shutil.copytree(MODEL, os.path.join(workspace, 'submission'), symlinks=True)
    os.makedirs(os.path.join(workspace, 'submission', '.git'))
    output = os.path.join(folder, 'github_output')
    open(output, 'w').close()
    env = dict(env, GITHUB_WORKSPACE=workspace, GITHUB_OUTPUT=output, **job_env)
    started = time.monotonic()
    pull = subprocess.run(['bash', '-e', '-c', steps['Course image']['run']], cwd=workspace, env=env,
                          stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True)
    pulled = time.monotonic()
    if pull.returncode:
        raise SystemExit('the step Course image failed:\n%s' % pull.stdout)
    grade = subprocess.Popen(['bash', '-e', '-c', steps['Grade']['run']], cwd=workspace, env=env,
                             stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True)
    first, total, log = None, None, []
    for line in grade.stdout:
        log.append(line)
        if first is None and CRITERION.match(line):
            first = time.monotonic()
        if line.startswith('total '):
            total = line.strip()
    if grade.wait() or first is None:
        raise SystemExit('the step Grade failed (exit %d):\n%s' % (grade.returncode, ''.join(log[-40:])))
    return pulled - started, first - pulled, total


def megabytes(count):
    return '%.0f MB' % (count / 1e6)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--suite', default='bookworm')
    parser.add_argument('--runs', type=int, default=1, help='pulls and gradings of each image (in turns)')
    parser.add_argument('--no-build', action='store_true', help='the images as they are (ros-course:SUITE, '
                        'ros-course-grader:SUITE)')
    parser.add_argument('--before', metavar='IMAGE', help='a third image measured first, e.g. the students\' image '
                        'before a change (docker tag it before the build moves ros-course:SUITE)')
    args = parser.parse_args()
    if os.geteuid() != 0:
        raise SystemExit('run as root: it starts a dockerd of its own')
    if not os.environ.get('DOCKER_HOST'):
        raise SystemExit('DOCKER_HOST is not set: the course\'s engine (tools/docker.sh) must answer there')
    started = time.monotonic()
    if args.no_build:
        full, grader = 'ros-course:%s' % args.suite, 'ros-course-grader:%s' % args.suite
    else:
        full, grader = build(args.suite)
    images = ([('before', args.before)] if args.before else []) + [('students\' image', full),
                                                                    ('grading image', grader)]
    sizes = {}
    for _, image in images:
        sizes[image] = (int(sh(['docker', 'image', 'inspect', '-f', '{{.Size}}', image])), compressed_bytes(image))
    folder = tempfile.mkdtemp(prefix='grading-image-bench-', dir='/var/tmp')
    registry = engine = None
    timings = {image: [] for _, image in images}
    try:
        registry, address = start_registry(folder)
        pushed = {}
        for _, image in images:
            name = '%s/course/%s' % (address, image)
            sh(['docker', 'tag', image, name])
            sh(['docker', 'push', '--quiet', name])
            sh(['docker', 'rmi', name])   # the tag only: this engine keeps its image
            pushed[image] = name
        engine_folder = os.path.join(folder, 'engine')
        os.makedirs(engine_folder)
        engine, env = start_engine(engine_folder)
        for run in range(args.runs):
            for _, image in (images if run % 2 == 0 else images[::-1]):   # in turns
                empty_engine(env, engine_folder)
                run_folder = tempfile.mkdtemp(prefix='run-', dir=folder)
                timings[image].append(classroom_run(pushed[image], env, run_folder))
                print('%s: pull %.1f s, grading to the first criterion %.1f s (%s)'
                      % ((image,) + timings[image][-1]), file=sys.stderr)
        empty_engine(env, engine_folder)
    finally:
        if engine:
            stop_process_group(engine, 60)
        if registry:
            stop_process_group(registry, 60)
        shutil.rmtree(folder, ignore_errors=True)
    load = os.getloadavg()
    print('\n### The grading image (%s, %d cores, load %.1f at the end; %d run%s of each)\n'
          % (args.suite, os.cpu_count(), load[0], args.runs, '' if args.runs == 1 else 's'))
    print('| image | size | compressed (gzip -1) | pull (local registry) | grading to the first criterion '
          '| pull to the first criterion | score |')
    print('|---|---|---|---|---|---|---|')
    for label, image in images:
        runs = timings[image]
        span = (lambda values: '%.1f s' % values[0] if len(values) == 1 else
                '%.1f to %.1f s' % (min(values), max(values)))
        print('| %s `%s` | %s | %s | %s | %s | %s | %s |' % (
            label, image, megabytes(sizes[image][0]), megabytes(sizes[image][1]), span([r[0] for r in runs]),
            span([r[1] for r in runs]), span([r[0] + r[1] for r in runs]),
            ', '.join(sorted({r[2] for r in runs}))))
    full_size, grader_size = sizes[full], sizes[grader]
    print('\nThe grading image: %.0f %% of the students\' image\'s size, %.0f %% compressed. Bench time %.0f s.'
          % (100.0 * grader_size[0] / full_size[0], 100.0 * grader_size[1] / full_size[1], time.monotonic() - started))


if __name__ == '__main__':
    main()
