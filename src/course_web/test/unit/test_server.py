"""The web server without ROS: files, Origin, bad messages, keys, and a page that does not read."""
import json
import socket

import tornado.httpclient
import tornado.testing
import tornado.websocket

from course_web.frames import Scenes
from course_web.server import ViewServer
from fake_tb3.world import load_world


class ServerTest(tornado.testing.AsyncTestCase):
    def setUp(self):
        super().setUp()
        self.scenes = Scenes()
        self.scenes.tb3.start(load_world('empty'), 'burger')
        self.keys, self.log = [], []
        self.server = ViewServer(self.scenes, self.keys.append, self.log.append)
        self.port = self.server.listen(0, '127.0.0.1')

    def tearDown(self):
        self.server.stop()
        super().tearDown()

    def url(self, path, scheme='http'):
        return '%s://127.0.0.1:%d%s' % (scheme, self.port, path)

    def connect(self, origin=None):
        origin = 'http://127.0.0.1:%d' % self.port if origin is None else origin
        request = tornado.httpclient.HTTPRequest(self.url('/ws', 'ws'), headers={'Origin': origin})
        return tornado.websocket.websocket_connect(request)

    @tornado.testing.gen_test
    def test_the_page_and_its_files_come_from_the_server(self):
        client = tornado.httpclient.AsyncHTTPClient()
        for path, text in (('/', 'view.js'), ('/', 'scene.js'), ('/view.js', 'WebSocket'), ('/scene.js', 'getContext'),
                           ('/view.css', 'canvas')):
            response = yield client.fetch(self.url(path))
            self.assertIn(text, response.body.decode())
        self.assertNotIn('http', (yield client.fetch(self.url('/'))).body.decode().replace('http://', ''))
        response = yield client.fetch(self.url('/../package.xml'), raise_error=False)
        self.assertIn(response.code, (403, 404))
        response = yield client.fetch(self.url('/'), headers={'Host': 'evil.example'}, raise_error=False)
        self.assertEqual(response.code, 403)

    @tornado.testing.gen_test
    def test_a_page_of_another_site_cannot_connect(self):
        with self.assertRaises(tornado.httpclient.HTTPClientError) as refused:
            yield self.connect('http://evil.example')
        self.assertEqual(refused.exception.code, 403)
        self.assertEqual(len(self.log), 1)
        self.assertIn("refused a websocket from Origin 'http://evil.example'", self.log[0])

    @tornado.testing.gen_test
    def test_keys_pass_and_a_bad_message_closes_only_its_own_page(self):
        good, bad = (yield self.connect()), (yield self.connect())
        first = json.loads((yield good.read_message()))
        self.assertTrue(first['tb3']['present'])
        yield bad.read_message()
        good.write_message(json.dumps({'key': 'w'}))
        bad.write_message(json.dumps({'key': 'w', 'topic': '/rosout'}))
        self.assertIsNone((yield bad.read_message()))  # closed
        self.assertEqual(bad.close_code, 1008)
        good.write_message(json.dumps({'key': 'ArrowUp'}))
        self.scenes.tb3.on_odom(1.0, 2.0, 0.5, 0.1, 0.0)
        self.server.notify()
        update = json.loads((yield good.read_message()))
        self.assertEqual(update['tb3']['pose'], [1.0, 2.0, 0.5])
        self.assertEqual(self.keys, ['w', 'ArrowUp'])
        self.assertEqual(len(self.log), 1)
        self.assertIn('closed a page from 127.0.0.1: expected {"key": NAME}', self.log[0])
        huge = yield self.connect()
        yield huge.read_message()
        huge.write_message('x' * 100000)
        self.assertIsNone((yield huge.read_message()))
        self.assertEqual(len(self.log), 2)
        self.assertIn('larger than', self.log[1])

    @tornado.testing.gen_test(timeout=20)
    def test_a_page_that_stops_reading_gets_no_queue_and_slows_nobody(self):
        stalled = socket.socket()
        stalled.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        stalled.connect(('127.0.0.1', self.port))
        stalled.sendall(('GET /ws HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nOrigin: http://127.0.0.1:%d\r\n'
                         'Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\n'
                         'Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n'
                         % (self.port, self.port)).encode())
        live = yield self.connect()
        yield live.read_message()
        for step in range(3000):  # 3000 states of a long scan: megabytes the stalled page never reads
            self.scenes.tb3.on_odom(step * 0.01, 0.0, 0.0, 0.0, 0.0)
            self.scenes.tb3.on_scan([1.0 + step * 1e-4] * 360, 0.0, 0.0175, 0.12, 3.5)
            self.server.notify()
            update = json.loads((yield live.read_message()))  # the live page reads every frame
            self.assertIn('pose', update['tb3'])
        stalled_page = [page for page in self.server.pages if page.request.headers.get('Sec-WebSocket-Key')
                        == 'dGhlIHNhbXBsZSBub25jZQ==']
        self.assertEqual(len(stalled_page), 1)
        print('frames sent to the stalled page: %d, to the live one: %d'
              % (stalled_page[0].frames_sent, max(page.frames_sent for page in self.server.pages)))
        self.assertTrue(stalled_page[0].sending)  # one frame on its way, nothing behind it
        self.assertLess(stalled_page[0].frames_sent, 300)
        self.assertGreater(max(page.frames_sent for page in self.server.pages), 2900)
        stalled.close()


def test_the_port_the_view_says_it_serves_on_is_read_back_from_its_output():
    from course_web.ros_view import SERVING, served_port
    said = '[INFO] [1796385147.248852]: ' + SERVING % ('localhost', 46587, '') + '\n'
    assert served_port('started\n' + said) == 46587
    assert served_port(SERVING % ('labserver', 8080, ' (listening on every address of this machine)')) == 8080
    assert served_port('course_web: cannot listen on 127.0.0.1 port 0: ...') is None
