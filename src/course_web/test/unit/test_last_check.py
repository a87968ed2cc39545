"""The student's last checks as the view finds and serves them (course_web.last_check): the folder
of each check, the pointer to the latest, the few kept, and only their known files served."""
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

import tornado.httpclient
import tornado.testing

from course_common.processes import free_port, port_open, stop_process_group
from course_common.waiting import wait_until
from course_web import last_check
from course_web.frames import Scenes
from course_web.server import ViewServer

NOON = time.mktime((2026, 11, 28, 12, 0, 0, 0, 0, -1))


def make_check(root, lab='move_turtlebot3', now=NOON, folder='move_turtlebot3'):
    """A check's folder as course_grader.check leaves it: check.json, a picture, a run's replay, a log."""
    check = last_check.new_check_folder(root, lab, now)
    os.makedirs(os.path.join(check, folder))
    last_check.write_summary(check, {'lab': lab, 'folder': folder})
    for name, data in (('trajectory.png', b'\x89PNG picture'), ('trajectory.replay.js', b'window.courseReplay = 1;'),
                       ('trajectory.log', b'a log'), ('result.json', b'{}')):
        with open(os.path.join(check, folder, name), 'wb') as stream:
            stream.write(data)
    last_check.point_latest(root, check)
    return check


def test_each_check_has_a_folder_of_its_own_named_by_its_time(tmp_path):
    root = str(tmp_path / 'course_check')
    first = last_check.new_check_folder(root, 'my_turtle', NOON)
    second = last_check.new_check_folder(root, 'my_turtle', NOON)
    assert first == os.path.join(root, 'my_turtle', '2026-11-28_12-00-00')
    assert second == first + '_2'
    assert os.listdir(first) == [] and os.listdir(second) == []


def test_latest_points_at_the_last_check_of_any_lab(tmp_path):
    root = str(tmp_path)
    assert last_check.latest_check(root) is None
    make_check(root, 'move_turtlebot3', NOON)
    assert last_check.latest_check(root) == 'move_turtlebot3/2026-11-28_12-00-00'
    make_check(root, 'my_turtle', NOON + 60, 'my_turtle')
    assert last_check.latest_check(root) == 'my_turtle/2026-11-28_12-01-00'
    assert os.readlink(os.path.join(root, 'latest')) == 'my_turtle/2026-11-28_12-01-00'


def test_a_pointer_that_is_not_to_a_check_of_ours_is_none(tmp_path):
    root = str(tmp_path)
    for target in ('/etc', '../elsewhere/2026-11-28_12-00-00', 'lab/not-a-stamp', 'lab/2026-11-28_12-00-00'):
        os.symlink(target, os.path.join(root, 'latest'))
        assert last_check.latest_check(root) is None, target
        os.remove(os.path.join(root, 'latest'))


def test_the_last_five_checks_of_each_lab_are_kept(tmp_path):
    root = str(tmp_path)
    assert last_check.KEEP_PER_LAB == 5
    for minute in range(7):
        make_check(root, 'my_turtle', NOON + 60 * minute, 'my_turtle')
        last_check.prune(root, 'my_turtle')
    make_check(root, 'ros_exercises', NOON, 'ros_exercises')
    os.makedirs(os.path.join(root, 'my_turtle', 'notes of mine'))
    assert last_check.prune(root, 'my_turtle') == []
    assert sorted(os.listdir(os.path.join(root, 'my_turtle'))) == [
        '2026-11-28_12-0%d-00' % minute for minute in range(2, 7)] + ['notes of mine']
    assert os.listdir(os.path.join(root, 'ros_exercises')) == ['2026-11-28_12-00-00']


def test_the_check_latest_points_at_is_never_removed(tmp_path):
    root = str(tmp_path)
    for minute in range(3):
        make_check(root, 'my_turtle', NOON + 60 * minute, 'my_turtle')
    last_check.point_latest(root, os.path.join(root, 'my_turtle', '2026-11-28_12-00-00'))
    assert last_check.prune(root, 'my_turtle', keep=1) == ['2026-11-28_12-01-00']


def test_only_a_checks_summary_pictures_and_replays_are_served(tmp_path):
    root = str(tmp_path)
    check = 'move_turtlebot3/2026-11-28_12-00-00'
    folder = make_check(root)
    assert last_check.served_file(root, check + '/check.json') == (
        os.path.join(folder, 'check.json'), 'application/json; charset=utf-8')
    assert last_check.served_file(root, check + '/move_turtlebot3/trajectory.png') == (
        os.path.join(folder, 'move_turtlebot3', 'trajectory.png'), 'image/png')
    assert last_check.served_file(root, check + '/move_turtlebot3/trajectory.replay.js')[1] == \
        'text/javascript; charset=utf-8'
    for refused in (check + '/move_turtlebot3/trajectory.log', check + '/move_turtlebot3/result.json',
                    check + '/move_turtlebot3/missing.png', check + '/move_turtlebot3', check,
                    check + '/check.json.part', 'latest/check.json', 'move_turtlebot3/latest/check.json',
                    'latest', '', '/etc/passwd', check + '/../../etc/x.png', check + '/move_turtlebot3/../check.json',
                    check + '/./check.json', check + '/.hidden/a.png', check + '/move_turtlebot3//trajectory.png',
                    'move_turtlebot3/2026-11-28_12-00-00/move_turtlebot3/sub/a.png'):
        assert last_check.served_file(root, refused) is None, refused


def test_no_symbolic_link_is_followed(tmp_path):
    root = str(tmp_path / 'checks')
    folder = make_check(root)
    outside = tmp_path / 'secret.png'
    outside.write_bytes(b'secret')
    os.symlink(str(outside), os.path.join(folder, 'move_turtlebot3', 'link.png'))
    os.symlink(str(tmp_path), os.path.join(folder, 'elsewhere'))
    os.symlink(os.path.join(folder, 'move_turtlebot3'), os.path.join(folder, 'again'))
    check = 'move_turtlebot3/2026-11-28_12-00-00'
    for refused in (check + '/move_turtlebot3/link.png', check + '/elsewhere/secret.png',
                    check + '/again/trajectory.png'):
        assert last_check.served_file(root, refused) is None, refused


class ServedTest(tornado.testing.AsyncTestCase):
    """The view's server on a folder of checks: what a browser gets from check/."""

    def setUp(self):
        super().setUp()
        self.root = tempfile.mkdtemp(prefix='course_check-')
        self.server = ViewServer(Scenes(), lambda key: None, lambda line: None, checks_root=self.root)
        self.port = self.server.listen(0, '127.0.0.1')

    def tearDown(self):
        self.server.stop()
        shutil.rmtree(self.root)
        super().tearDown()

    def fetch(self, path):
        return tornado.httpclient.AsyncHTTPClient().fetch('http://127.0.0.1:%d%s' % (self.port, path),
                                                          raise_error=False)

    @tornado.testing.gen_test
    def test_the_latest_check_and_its_files_with_their_types(self):
        answer = yield self.fetch('/check/latest')
        assert json.loads(answer.body) == {'check': None}
        make_check(self.root)
        answer = yield self.fetch('/check/latest')
        assert answer.headers['Content-Type'].startswith('application/json')
        assert json.loads(answer.body) == {'check': 'move_turtlebot3/2026-11-28_12-00-00'}
        base = '/check/move_turtlebot3/2026-11-28_12-00-00/'
        answer = yield self.fetch(base + 'check.json')
        assert json.loads(answer.body) == {'lab': 'move_turtlebot3', 'folder': 'move_turtlebot3'}
        answer = yield self.fetch(base + 'move_turtlebot3/trajectory.png')
        assert (answer.code, answer.headers['Content-Type'], answer.body) == (200, 'image/png', b'\x89PNG picture')
        assert answer.headers['X-Content-Type-Options'] == 'nosniff'
        answer = yield self.fetch(base + 'move_turtlebot3/trajectory.replay.js')
        assert answer.headers['Content-Type'].startswith('text/javascript')
        answer = yield self.fetch(base + '_player/replay.html')   # the player, beside the runs
        assert answer.code == 200 and b'replay.js' in answer.body

    @tornado.testing.gen_test
    def test_other_files_and_paths_out_are_not_found(self):
        make_check(self.root)
        with open(os.path.join(os.path.dirname(self.root), 'outside.png'), 'wb') as stream:
            stream.write(b'outside')
        base = '/check/move_turtlebot3/2026-11-28_12-00-00/'
        for path in (base + 'move_turtlebot3/trajectory.log', base + 'move_turtlebot3/result.json',
                     base + '..%2f..%2foutside.png', '/check/..%2Foutside.png', '/check/%2e%2e/outside.png',
                     base + 'move_turtlebot3%2f..%2fcheck.json', '/check/latest/check.json'):
            answer = yield self.fetch(path)
            assert answer.code == 404, path
        os.remove(os.path.join(os.path.dirname(self.root), 'outside.png'))

    @tornado.testing.gen_test
    def test_checks_cannot_be_changed_from_a_page(self):
        make_check(self.root)
        request = tornado.httpclient.HTTPRequest(
            'http://127.0.0.1:%d/check/move_turtlebot3/2026-11-28_12-00-00/check.json' % self.port,
            method='PUT', body='{}')
        answer = yield tornado.httpclient.AsyncHTTPClient().fetch(request, raise_error=False)
        assert answer.code == 405
        with open(os.path.join(self.root, 'move_turtlebot3', '2026-11-28_12-00-00', 'check.json')) as stream:
            assert json.load(stream)['lab'] == 'move_turtlebot3'


def test_without_a_master_follow_master_still_serves_the_last_check(tmp_path):
    """In the Docker image a student's check needs no master of theirs: follow_master serves the
    page and the last check while none runs."""
    root = tmp_path / 'course_check'
    make_check(str(root))
    port, no_master = free_port(), free_port()
    env = dict(os.environ, ROS_HOME=str(tmp_path), ROS_MASTER_URI='http://localhost:%d/' % no_master)
    follower = subprocess.Popen([sys.executable, '-m', 'course_web.follow_master', str(port)], env=env,
                                start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: port_open(port), 30, 'follow_master to serve port %d' % port, poll=0.05)
        with urllib.request.urlopen('http://localhost:%d/check/latest' % port, timeout=5) as answer:
            assert json.load(answer) == {'check': 'move_turtlebot3/2026-11-28_12-00-00'}
        with urllib.request.urlopen('http://localhost:%d/' % port, timeout=5) as answer:
            assert b'last_check.js' in answer.read()
        # A `kill` of follow_master alone (not its group) stops the server it started too.
        follower.send_signal(signal.SIGTERM)
        follower.wait(10)
        wait_until(lambda: not port_open(port), 10, 'the page\'s server to stop with follow_master', poll=0.05)
    finally:
        assert stop_process_group(follower, timeout=10) is not None
    assert not port_open(port)
