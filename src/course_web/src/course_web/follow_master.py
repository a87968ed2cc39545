"""In the course's Docker image: the page of whichever lab runs, with no step of the student's.

Waits for a ROS master (ROS_MASTER_URI), runs the view node on it listening on every address of
the container (so `docker run -p 127.0.0.1:8080:8080` reaches it), and stops it when that master
goes away; the next lab's master gets a new one. The page reconnects by itself. While no master
runs, the same server without ROS serves the page and "Your last check" (a student's check needs
no master of theirs), with no world to show.
"""
import asyncio
import os
import signal
import subprocess
import sys
import time

import rosgraph

from course_common.processes import exit_on_terminate, stop_process_group

POLL = 0.5  # s
VIEW_NODE = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'nodes', 'view')


def master_online():
    try:
        return rosgraph.is_master_online()
    except Exception:  # a malformed ROS_MASTER_URI is as good as no master
        return False


def view_environment():
    """Our environment without ros_loopback's preloaded library, which would move the page's
    0.0.0.0 to loopback, out of `docker run -p`'s reach. (The node's ROS sockets stay on loopback:
    rospy binds them there itself while ROS_HOSTNAME is localhost.)"""
    env = dict(os.environ)
    kept = [entry for entry in env.get('LD_PRELOAD', '').split(':')
            if entry and not entry.endswith('/libros_loopback.so')]
    if kept:
        env['LD_PRELOAD'] = ':'.join(kept)
    else:
        env.pop('LD_PRELOAD', None)
    return env


def serve_without_master(port):
    """The view's server with no simulator and no keys, until SIGINT or SIGTERM."""
    import tornado.ioloop
    from course_web.frames import Scenes
    from course_web.server import ViewServer
    server = ViewServer(Scenes(), lambda key: None, lambda line: print(line, file=sys.stderr, flush=True))
    server.listen(int(port), '0.0.0.0')
    loop = tornado.ioloop.IOLoop.current()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        asyncio.get_event_loop().add_signal_handler(signal_number, loop.stop)
    loop.start()
    server.stop()


def main(argv=None):
    args = list(sys.argv[1:] if argv is None else argv)
    if args[:1] == ['--without-master']:
        serve_without_master(args[1])
        return
    port = args[0] if args else os.environ.get('COURSE_WEB_PORT', '8080')
    exit_on_terminate()   # a `kill` stops the page's server or view it started (its finally)
    while True:
        if not master_online():
            idle = subprocess.Popen([sys.executable, '-m', 'course_web.follow_master', '--without-master', port],
                                    start_new_session=True, env=view_environment())
            try:
                while not master_online():
                    time.sleep(POLL)
            finally:
                stop_process_group(idle, timeout=5.0)
        view = subprocess.Popen([sys.executable, VIEW_NODE, '__name:=course_web', '_host:=0.0.0.0',
                                 '_port:=%s' % port], start_new_session=True, env=view_environment())
        try:
            while view.poll() is None and master_online():
                time.sleep(POLL)
        finally:
            stop_process_group(view, timeout=5.0)
        if view.returncode not in (0, -2):
            time.sleep(5 * POLL)  # it failed by itself (port taken?): its log said why


if __name__ == '__main__':
    main()
