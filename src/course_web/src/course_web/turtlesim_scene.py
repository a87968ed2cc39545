"""turtlesim as the page draws it, rebuilt from turtlesim's ~scene messages (pure: no ROS).

The path layer (background and pen lines, no turtles) is kept as turtlesim's first message gave it
plus the drawing operations since, in order; a page that connects gets the layer as a PNG and
then only the new operations. Turtles come as turtlesim sends them: all of them with a picture,
then those that changed and the names of those killed; a page one version behind gets just that,
any other page the whole list. The layer is drawn with turtlesim's own canvas code, so a PNG sent to
a new page is the pixels turtlesim has.
"""
import base64
import io
import zlib

import numpy as np

from turtlesim.canvas import Canvas

MAX_PENDING_OPS = 5000  # operations kept unflattened; a page further behind gets a new PNG
MAX_CANVAS_SIDE = 4096


class SceneError(ValueError):
    """A ~scene message that cannot be applied; the text says why."""


def _number(value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError('expected a number, got %r' % (value,))
    return value


def _channel(value):
    value = _number(value)
    if not (isinstance(value, int) and 0 <= value <= 255):
        raise SceneError('expected a colour channel 0..255, got %r' % (value,))
    return value


def parse_op(op):
    """A drawing operation as a tuple, checked: ('fill', (r, g, b)) or ('line', x0, y0, x1, y1, (r, g, b), width)."""
    if isinstance(op, list) and len(op) == 4 and op[0] == 'fill':
        return ('fill', tuple(_channel(c) for c in op[1:]))
    if isinstance(op, list) and len(op) == 9 and op[0] == 'line':
        x0, y0, x1, y1 = (float(_number(v)) for v in op[1:5])
        width = _number(op[8])
        if not 0 <= width <= 255:
            raise SceneError('pen width %r out of 0..255' % (width,))
        return ('line', x0, y0, x1, y1, tuple(_channel(c) for c in op[5:8]), width)
    raise SceneError('unknown drawing operation %r' % (op,))


_REAL = (int, float)


def check_turtles(turtles):
    """The turtles list itself, once each entry is checked to be [name, x, y, theta, icon]: one
    tight loop, as 100 turtles come at every tick."""
    if not isinstance(turtles, list):
        raise SceneError('expected a list of turtles, got %r' % (turtles,))
    for turtle in turtles:
        if not (type(turtle) is list and len(turtle) == 5 and type(turtle[0]) is str
                and type(turtle[1]) in _REAL and type(turtle[2]) in _REAL
                and type(turtle[3]) in _REAL and type(turtle[4]) is int):
            raise SceneError('expected [name, x, y, theta, icon], got %r' % (turtle,))
    return turtles


def decode_canvas(canvas):
    height, width = int(_number(canvas['height'])), int(_number(canvas['width']))
    if not (0 < height <= MAX_CANVAS_SIDE and 0 < width <= MAX_CANVAS_SIDE):
        raise SceneError('canvas of %dx%d pixels' % (width, height))
    raw = zlib.decompress(base64.b64decode(canvas['rgb_zlib_base64']), bufsize=height * width * 3)
    if len(raw) != height * width * 3:
        raise SceneError('canvas of %d bytes for %dx%d pixels' % (len(raw), width, height))
    return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3)


def apply_op(canvas, op):
    if op[0] == 'fill':
        canvas.fill(op[1])
    else:
        canvas.draw_line(*op[1:])


def png_bytes(pixels):
    from PIL import Image
    stream = io.BytesIO()
    Image.fromarray(pixels, 'RGB').save(stream, format='PNG', compress_level=1)
    return stream.getvalue()


class TurtlesimScene:
    """The canvas and turtles of one turtlesim. `generation` changes when the picture is replaced
    as a whole (turtlesim started, restarted or gone), `version` with every change."""

    def __init__(self):
        self.present = False
        self.generation = 0
        self.version = 0
        self.seq = None
        self.stamp = None
        self.turtles = {}  # name -> [name, x, y, theta, icon], in the order turtlesim first sent them
        self.changed = []  # the turtles the last message changed, and the names it removed
        self.gone = []
        self._canvas = None  # turtlesim.canvas.Canvas with the first _flat ops applied
        self._flat = 0
        self._pending = []  # ops after the first _flat ones, not yet drawn on _canvas
        self._png = None  # (op count, PNG bytes) of the last PNG made

    @property
    def op_count(self):
        return self._flat + len(self._pending)

    def apply(self, message):
        """Apply one ~scene message (a dict). Returns False when a message was missed (the caller
        asks turtlesim for a new picture); raises SceneError on a malformed message."""
        try:
            if 'canvas' in message:
                pixels = decode_canvas(message['canvas'])
                canvas = Canvas((0, 0, 0))
                canvas.pixels = pixels.copy()
                self._canvas, self._flat, self._pending, self._png = canvas, 0, [], None
                self.present = True
                self.generation += 1
            elif self.seq is None or not self.present or message['seq'] != self.seq + 1:
                return False
            ops = [parse_op(op) for op in message.get('ops', [])]
            changed = check_turtles(message['turtles'])
            gone = message.get('gone', [])
            if not (isinstance(gone, list) and all(type(name) is str for name in gone)):
                raise SceneError('expected a list of names, got %r' % (gone,))
            seq, stamp = int(_number(message['seq'])), float(_number(message['stamp']))
        except (KeyError, TypeError, ValueError, zlib.error) as error:
            raise SceneError('bad ~scene message: %s' % error) from None
        if 'canvas' in message:
            self.turtles = {}
        for name in gone:
            self.turtles.pop(name, None)
        for turtle in changed:
            self.turtles[turtle[0]] = turtle
        self._pending.extend(ops)
        self.changed, self.gone, self.seq, self.stamp = changed, gone, seq, stamp
        self.version += 1
        if len(self._pending) > MAX_PENDING_OPS:
            self._flatten()
        return True

    def vanish(self):
        """turtlesim is gone: nothing to show until it publishes again."""
        if self.present or self.seq is not None:
            self.present, self.seq, self.turtles = False, None, {}
            self._canvas, self._flat, self._pending, self._png = None, 0, [], None
            self.generation += 1
            self.version += 1

    def _flatten(self):
        for op in self._pending:
            apply_op(self._canvas, op)
        self._flat += len(self._pending)
        self._pending = []

    def ops_since(self, index):
        """The operations after the first `index`, or None if they are no longer kept."""
        if index < self._flat:
            return None
        return self._pending[index - self._flat:]

    def png(self):
        """(op count, PNG bytes) of the path layer now."""
        if self._png is None or self._png[0] != self.op_count:
            self._flatten()
            self._png = (self.op_count, png_bytes(self._canvas.pixels))
        return self._png

    def pixels(self):
        """The path layer now, as an RGB array (for tests)."""
        self._flatten()
        return self._canvas.pixels.copy()


def op_for_page(op):
    """An operation as the page's JSON: ["fill", r, g, b] or ["line", x0, y0, x1, y1, r, g, b, w]."""
    if op[0] == 'fill':
        return ['fill'] + list(op[1])
    return ['line'] + [round(v, 3) for v in op[1:5]] + list(op[5]) + [op[6]]
