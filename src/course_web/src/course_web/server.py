"""The web server: the page's files and one websocket per page (tornado; no ROS here).

Every file the page needs is in this package's web/ folder: no CDN, no build step. A page's
websocket gets frames (frames.Scenes) and sends key presses, which go to `on_key`. Frames are sent
one at a time: the next is made only when the previous one has been handed to the socket, so a slow
or stalled page skips states and nothing queues up for it. A frame's websocket message is made once
for all the pages that get it and handed to each page's socket in one non-blocking send (the web
library's own path makes and buffers the message for each page: about 35 us more a frame and page).
`on_pages` hears how many pages are connected, so that the ROS side listens to the simulators only
while someone watches. check/ serves the student's last checks (course_web.last_check), read-only.
"""
import json
import logging
import os
import socket
import threading
import time

import tornado.httpserver
import tornado.iostream
import tornado.ioloop
import tornado.netutil
import tornado.web
import tornado.websocket

from course_web import last_check
from course_web.frames import NEW_PAGE
from course_web.origin import host_allowed, origin_allowed
from course_web.pacing import KeyBudget
from course_web.protocol import MAX_TRANSPORT_BYTES, ProtocolError, parse_client_message

WEB_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'web')
SEND_BUFFER_BYTES = 64 * 1024  # what the kernel may hold for a page that does not read
# Tornado logs a line per request and a traceback per bad websocket frame: our own one line is enough.
for _name in ('tornado.access', 'tornado.application', 'tornado.general'):
    logging.getLogger(_name).setLevel(logging.CRITICAL)


class _HostChecked:
    def prepare(self):
        if not host_allowed(self.request.host, self.application.settings['allowed_hosts']):
            self.application.settings['log']('course_web: refused a request for Host %r (not a name of '
                                             'this machine; see ~allowed_hosts)' % self.request.host)
            raise tornado.web.HTTPError(403)


class PageFiles(_HostChecked, tornado.web.StaticFileHandler):
    def set_extra_headers(self, path):
        self.set_header('Cache-Control', 'no-cache')
        self.set_header('X-Frame-Options', 'DENY')
        self.set_header('Content-Security-Policy', "default-src 'self'; img-src 'self' data:; "
                        "connect-src 'self'; frame-ancestors 'none'")


class CheckFiles(_HostChecked, tornado.web.RequestHandler):
    """check/latest: {"check": "LAB/STAMP" or null}; check/LAB/STAMP/...: that check's known files."""

    def get(self, path):
        root = self.application.settings['checks_root']
        self.set_header('Cache-Control', 'no-cache')
        self.set_header('X-Content-Type-Options', 'nosniff')
        self.set_header('Content-Security-Policy', "default-src 'none'; frame-ancestors 'none'")
        if path == 'latest':
            self.set_header('Content-Type', 'application/json; charset=utf-8')
            self.finish(json.dumps({'check': last_check.latest_check(root)}))
            return
        found = last_check.served_file(root, path)
        if found is None:
            raise tornado.web.HTTPError(404)
        file_path, content_type = found
        try:
            handle = os.open(file_path, os.O_RDONLY | os.O_NOFOLLOW)
        except OSError:
            raise tornado.web.HTTPError(404) from None
        with os.fdopen(handle, 'rb') as stream:
            body = stream.read()
        self.set_header('Content-Type', content_type)
        self.finish(body)


class PageSocket(_HostChecked, tornado.websocket.WebSocketHandler):
    def initialize(self, server):
        self.server = server
        self.cursor = NEW_PAGE
        self.sending = False
        self.budget = KeyBudget()
        self.closing_reason = None
        self.frames_sent = 0

    def check_origin(self, origin):
        if origin_allowed(origin, self.request.host, self.application.settings['allowed_hosts']):
            return True
        self.server.log('course_web: refused a websocket from Origin %r (this page is %r)'
                        % (origin, self.request.host))
        return False

    def open(self):
        connection = self.ws_connection.stream.socket
        connection.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SEND_BUFFER_BYTES)
        connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.server.page_opened(self)
        self.offer()

    def on_message(self, message):
        try:
            key = parse_client_message(message)
        except ProtocolError as error:
            self.refuse(str(error), 1003 if isinstance(message, bytes) else 1008)
            return
        if self.budget.allow(time.monotonic()):
            self.server.on_key(key)

    def refuse(self, reason, code):
        self.closing_reason = reason
        self.server.log('course_web: closed a page from %s: %s' % (self.request.remote_ip, reason))
        self.close(code, reason[:100])

    def on_close(self):
        self.server.page_closed(self)
        if self.close_code is None and self.closing_reason is None:
            # No closing handshake: the web library dropped it for a message larger than
            # MAX_TRANSPORT_BYTES (it does not say so), or the network went away.
            self.server.log('course_web: closed a page from %s: a message larger than %d bytes, '
                            'or the connection broke' % (self.request.remote_ip, MAX_TRANSPORT_BYTES))

    def offer(self):
        """Send the page what changed, unless a frame to it is still on its way."""
        if self.sending or self.ws_connection is None or self.ws_connection.is_closing():
            return
        message, self.cursor = self.server.scenes.message_for(self.cursor)
        if message is None:
            return
        self.frames_sent += 1
        stream = self.ws_connection.stream
        sent = 0
        if not stream.writing():  # nothing of the library's (a ping, a close) is queued before it
            try:
                sent = stream.socket.send(message)
            except BlockingIOError:
                pass
            except OSError:
                return  # the connection broke: the library closes the page when it reads
        # Usually the socket took the whole frame at once: the page can have the next one at the
        # next change. Otherwise the rest goes through the library's stream, and the next frame
        # waits until it has left.
        if sent < len(message):
            try:
                future = stream.write(message[sent:])
            except tornado.iostream.StreamClosedError:
                return
            self.sending = True
            future.add_done_callback(self._sent)

    def _sent(self, future):
        self.sending = False
        if not future.cancelled() and future.exception() is None:
            self.offer()


class ViewServer:
    """Serves the page and pushes frames; notify() may be called from any thread."""

    def __init__(self, scenes, on_key, log, allowed_hosts=(), on_pages=None, checks_root=None):
        self.scenes = scenes
        self.on_key = on_key
        self.log = log
        self.on_pages = on_pages or (lambda count: None)
        self.pages = set()
        self.loop = None
        self._flush_due = None  # monotonic time by which a flush is scheduled, None: none is
        self._flush_timer = None  # the loop's timeout for a flush that may wait, if one is set
        self._flush_lock = threading.Lock()
        self.app = tornado.web.Application([
            (r'/ws', PageSocket, {'server': self}),
            # A check's player (replay.html) beside its folders, as in the teacher's report, so
            # that it finds ../FOLDER/RUN.replay.js.
            (r'/check/[^/]+/[^/]+/_player/(.*)', PageFiles, {'path': os.path.normpath(WEB_DIR)}),
            (r'/check/(.*)', CheckFiles),
            (r'/(.*)', PageFiles, {'path': os.path.normpath(WEB_DIR), 'default_filename': 'index.html'}),
        ], websocket_max_message_size=MAX_TRANSPORT_BYTES, allowed_hosts=tuple(allowed_hosts),
            log=log, checks_root=checks_root or last_check.default_root(),
            websocket_ping_interval=10, websocket_ping_timeout=30)
        self.http = None

    def listen(self, port, address):
        """Bind (in the thread that will run the loop); returns the port (useful with port 0)."""
        self.loop = tornado.ioloop.IOLoop.current()
        self.http = tornado.httpserver.HTTPServer(self.app, max_body_size=MAX_TRANSPORT_BYTES)
        sockets = tornado.netutil.bind_sockets(port, address)
        self.http.add_sockets(sockets)
        return sockets[0].getsockname()[1]

    def page_opened(self, page):
        self.pages.add(page)
        self.on_pages(len(self.pages))

    def page_closed(self, page):
        if page in self.pages:
            self.pages.discard(page)
            self.on_pages(len(self.pages))

    def notify(self, within=0.0):
        """Something changed: offer every page a frame, at the latest `within` seconds from now
        (in the loop's thread). Changes that come meanwhile ride along in the same frame."""
        due = time.monotonic() + within
        with self._flush_lock:
            if self.loop is None or not self.pages or (self._flush_due is not None and self._flush_due <= due):
                return
            self._flush_due = due
        self.loop.add_callback(self._schedule_flush, within)

    def _schedule_flush(self, within):
        if within > 0:
            self._cancel_flush_timer()
            self._flush_timer = self.loop.call_later(within, self._flush)
        else:
            self._flush()

    def _cancel_flush_timer(self):
        if self._flush_timer is not None:
            self.loop.remove_timeout(self._flush_timer)
            self._flush_timer = None

    def _flush(self):
        # A change that could wait (a TurtleBot3 update waiting for turtlesim's tick) goes in this
        # frame: its own timeout would only wake the loop for nothing.
        self._cancel_flush_timer()
        with self._flush_lock:
            self._flush_due = None
        for page in list(self.pages):
            page.offer()

    def stop(self):
        """In the loop's thread: close the listening sockets and every page."""
        if self.http is not None:
            self.http.stop()
        for page in list(self.pages):
            page.close(1001, 'server stopping')
