"""What each page is sent (pure): the scenes, and per page a cursor saying what it already has.

A page is sent a frame only when the previous one has left (the server asks for the next frame
then), and the frame is made from the scenes as they are at that moment: a slow page skips states,
it never gets a queue of old ones. Pages that have the same things get the same frame, made once:
its text and its bytes on the wire (a websocket message).
"""
import base64
import threading

from course_web.protocol import encode_frame, websocket_text_frame
from course_web.tb3_scene import Tb3Scene
from course_web.turtlesim_scene import TurtlesimScene, op_for_page

# (turtlesim generation, version, op count; tb3 generation, version, trail end, scan seq)
NEW_PAGE = (-1, -1, 0, -1, -1, 0, -1)


class Scenes:
    """Both simulators' scenes behind one lock: the ROS threads change them, the web thread reads."""

    def __init__(self):
        self.lock = threading.Lock()
        self.turtlesim = TurtlesimScene()
        self.tb3 = Tb3Scene()
        self._made = {}  # cursor -> (frame text, its websocket message, cursor after it), for the current versions
        self._made_at = None

    def _cursor_now(self):
        ts, tb = self.turtlesim, self.tb3
        return (ts.generation, ts.version, ts.op_count, tb.generation, tb.version, tb.trail_end,
                tb.scan_seq)

    def frame_for(self, cursor):
        """(frame text or None if the page is up to date, the page's cursor after it)."""
        made = self._made_for(cursor)
        return (None, cursor) if made is None else (made[0], made[2])

    def message_for(self, cursor):
        """frame_for's frame as the bytes of a websocket message, the same object for every page."""
        made = self._made_for(cursor)
        return (None, cursor) if made is None else (made[1], made[2])

    def _made_for(self, cursor):
        with self.lock:
            now = self._cursor_now()
            if now[:2] == cursor[:2] and now[3:5] == cursor[3:5]:
                return None
            if self._made_at != now:
                self._made, self._made_at = {}, now
            made = self._made.get(cursor)
            if made is None:
                text = encode_frame(self._frame(cursor))
                made = self._made[cursor] = (text, websocket_text_frame(text), now)
            return made

    def _frame(self, cursor):
        ts_generation, ts_version, ts_ops, tb_generation, tb_version, trail_end, scan_seq = cursor
        frame = {}
        ts = self.turtlesim
        if (ts.generation, ts.version) != (ts_generation, ts_version):
            part = {'present': ts.present}
            if ts.present:
                ops = ts.ops_since(ts_ops) if ts.generation == ts_generation else None
                if ops is None:
                    _, png = ts.png()
                    part['canvas'] = 'data:image/png;base64,' + base64.b64encode(png).decode('ascii')
                    ops = []
                part.update(ops=[op_for_page(op) for op in ops], seq=ts.seq, stamp=ts.stamp)
                if ts.generation == ts_generation and ts.version == ts_version + 1:
                    part.update(turtles=ts.changed, gone=ts.gone)  # the page has the rest
                else:
                    part.update(turtles=list(ts.turtles.values()), all=True)
            frame['turtlesim'] = part
        tb = self.tb3
        if (tb.generation, tb.version) != (tb_generation, tb_version):
            part = {'present': tb.present}
            if tb.present:
                trail = tb.trail_since(trail_end) if tb.generation == tb_generation else None
                if trail is None:
                    part.update(world=tb.world, body=tb.body, trail_reset=True)
                    trail = tb.trail
                part['trail'] = trail
                if tb.pose is not None:
                    part.update(pose=[round(v, 4) for v in tb.pose],
                                speed=[round(v, 4) for v in tb.speed],
                                closest=None if tb.closest is None else round(tb.closest, 3))
                if tb.scan_seq != scan_seq or tb.generation != tb_generation:
                    part['scan'] = tb.scan
            frame['tb3'] = part
        return frame
