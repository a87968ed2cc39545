#!/usr/bin/env python3
"""CI, after the tests in an image: the browser view as a student on macOS or Windows gets it.

Starts a container of IMAGE as `docker run -it` would (COURSE_WEB=1 stands for the terminal, so the
image's entry point starts course_web's follow_master), runs turtlesim's square demo in it, and
reads the page's websocket from outside the container, on this machine's own non-loopback address:
what `docker run -p 127.0.0.1:8080:8080` forwards to, which a view listening on loopback only
would refuse. Passes when the frames show turtle1 moving. The engine here has no bridge network
(`-p` cannot be tried on it), so the containers share the host's network, on free ports. The host
needs only python3 and docker: the page is read by a second container of the image.

Usage: tools/docker-view-check.py IMAGE
"""
import asyncio
import json
import math
import subprocess
import sys
import time
import uuid


WAIT_SECONDS = 90  # the container's start, roslaunch and the view's start, on a busy machine


def own_address():
    """This machine's first global IPv4 address, or loopback when it has none."""
    words = subprocess.run(['ip', '-4', '-o', 'addr', 'show', 'scope', 'global'], stdout=subprocess.PIPE,
                           universal_newlines=True).stdout.split()
    addresses = [words[i + 1].split('/')[0] for i, word in enumerate(words) if word == 'inet']
    return addresses[0] if addresses else '127.0.0.1'


async def turtle_moving(url, origin, deadline):
    """turtle1's first and latest (x, y) in the page's frames once it has moved 0.1 m, reconnecting
    until the deadline as the page does."""
    from tornado.httpclient import HTTPRequest
    from tornado.websocket import websocket_connect
    first, last = None, 'no connection'
    while time.monotonic() < deadline:
        try:
            socket = await websocket_connect(HTTPRequest(url, headers={'Origin': origin}, connect_timeout=5))
        except Exception as error:  # not up yet
            last = 'connecting: %r' % error
            await asyncio.sleep(1.0)
            continue
        while time.monotonic() < deadline:
            frame = await socket.read_message()
            if frame is None:
                last = 'the view closed the connection'
                break
            turtles = json.loads(frame).get('turtlesim', {}).get('turtles', [])
            poses = [turtle[1:3] for turtle in turtles if turtle[0] == 'turtle1']
            if poses:
                first = first or poses[0]
                if math.hypot(poses[0][0] - first[0], poses[0][1] - first[1]) >= 0.1:
                    socket.close()
                    return first, poses[0]
            last = 'turtle1 not moving in the frames (last: %s)' % frame[:120]
    raise SystemExit('docker-view-check: turtle1 not seen moving within %d s: %s' % (WAIT_SECONDS, last))


def in_image(image, name, command, **run):
    """`command` (bash, after tools/env.sh) in a container of the image on the host's network."""
    return subprocess.run(['docker', 'run', '--rm', '--name', name, '--network', 'host', image, 'bash', '-c',
                           'source tools/env.sh >/dev/null && ' + command], universal_newlines=True, **run)


def main(image):
    """On the host: needs only the docker command; the ports and the page's reader come from the image."""
    run = uuid.uuid4().hex[:8]
    ports = in_image(image, 'course-view-ports-' + run, 'exec python3 -c "from course_common.processes import '
                     'free_port; print(free_port(), free_port())"', stdout=subprocess.PIPE, check=True)
    page_port, master_port = (int(port) for port in ports.stdout.split())
    lab = 'course-view-lab-' + run
    subprocess.run(['docker', 'run', '-d', '--rm', '--name', lab, '--network', 'host', '-e', 'COURSE_WEB=1',
                    '-e', 'COURSE_WEB_PORT=%d' % page_port, '-e', 'ROS_MASTER_URI=http://localhost:%d' % master_port,
                    image, 'bash', '-c', 'source tools/env.sh && export ROS_MASTER_URI=http://localhost:%d && exec '
                    'roslaunch -p %d turtlesim draw_square_demo.launch' % (master_port, master_port)],
                   check=True, stdout=subprocess.DEVNULL)
    reader = 'course-view-reader-' + run
    try:
        watched = in_image(image, reader, 'exec python3 tools/docker-view-check.py --watch %d' % page_port,
                           timeout=WAIT_SECONDS + 30)
        if watched.returncode != 0:
            log = subprocess.run(['docker', 'exec', lab, 'cat', '/home/student/.ros/course_web.log'],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True).stdout
            print('docker-view-check: course_web.log in the container:\n' + log[-2000:], file=sys.stderr)
            raise SystemExit('docker-view-check: %s does not show a running lab to the outside' % image)
    finally:
        subprocess.run(['docker', 'rm', '-f', lab, reader], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def watch(page_port):
    """In a container on the host's network: reads the page's websocket on the host's own address."""
    from tornado.ioloop import IOLoop
    started = time.monotonic()
    address = own_address()
    if address == '127.0.0.1':
        print('docker-view-check: this machine has no global address: the view is read on loopback only')
    url = 'ws://%s:%d/ws' % (address, page_port)
    first, latest = IOLoop.current().run_sync(
        lambda: turtle_moving(url, 'http://%s:%d' % (address, page_port), started + WAIT_SECONDS))
    print('docker-view-check: the page at %s showed turtle1 moving from (%.2f, %.2f) to (%.2f, %.2f) after %.1f s'
          % (url, first[0], first[1], latest[0], latest[1], time.monotonic() - started))


if __name__ == '__main__':
    if len(sys.argv) == 3 and sys.argv[1] == '--watch':
        watch(int(sys.argv[2]))
    elif len(sys.argv) == 2:
        main(sys.argv[1])
    else:
        raise SystemExit(__doc__.strip().splitlines()[-1])
