"""The path layer: a 500x500 RGB picture of the background and the pen lines (no turtles on it).

Pixel coordinates are those of the original's Qt widget: column = x * 45, row = (H - y) * 45, and
pixel (col, row) is the one whose centre is at (col, row), so round(position) names the pixel under
a point. Lines are drawn aliased with square caps: every pixel whose centre lies inside the stroke
rectangle (the segment widened by the pen width and extended by half the width at both ends) takes
the pen colour.
"""
import math

import numpy as np

CANVAS_PX = 500


def _clip_segment(x0, y0, x1, y1, low, high):
    """Liang-Barsky: the part of the segment inside the square [low, high]^2, or None.

    Keeps far teleport lines cheap and their arithmetic small; the clipped ends lie outside the
    canvas, so the caps they lose are never visible. A clipped end is put exactly on the edge that
    cut it, so that lines from very far away (where x0 + t * dx has no precision left) stay put.
    """
    start, end = (0.0, None), (1.0, None)  # (t, (axis, edge value) of the cut or None)
    dx, dy = x1 - x0, y1 - y0
    for axis, step, room, edge in ((0, -dx, x0 - low, low), (0, dx, high - x0, high),
                                   (1, -dy, y0 - low, low), (1, dy, high - y0, high)):
        if step == 0:
            if room < 0:
                return None
            continue
        t = room / step
        if step < 0:
            if t > end[0]:
                return None
            if t > start[0]:
                start = (t, (axis, edge))
        else:
            if t < start[0]:
                return None
            if t < end[0]:
                end = (t, (axis, edge))
    points = []
    for t, cut in (start, end):
        point = [x0 + t * dx, y0 + t * dy]
        if cut is not None:
            point[cut[0]] = cut[1]
        points.extend(point)
    return tuple(points)


class Canvas:
    """The path image; `version` changes whenever a pixel may have changed."""

    def __init__(self, background):
        self.pixels = np.empty((CANVAS_PX, CANVAS_PX, 3), dtype=np.uint8)
        self.version = 0
        self.fill(background)

    def fill(self, color):
        self.pixels[:, :] = color
        self.version += 1

    def pixel(self, col, row):
        """The (r, g, b) at a pixel, as ints."""
        return tuple(self.pixels[row, col].tolist())

    def draw_line(self, x0, y0, x1, y1, color, width):
        """Aliased, square-capped line between two points given in pixel coordinates."""
        half = width / 2.0
        margin = width + 2.0
        low, high = -margin, CANVAS_PX - 1 + margin
        if not (low <= min(x0, x1) and max(x0, x1) <= high and low <= min(y0, y1) and max(y0, y1) <= high):
            clipped = _clip_segment(x0, y0, x1, y1, low, high)
            if clipped is None:
                return
            x0, y0, x1, y1 = clipped
        dx, dy = x1 - x0, y1 - y0
        length = math.hypot(dx, dy)
        if length > 0.0:
            ux, uy = dx / length, dy / length
        else:  # a point: the square cap still paints a width x width square
            ux, uy = 1.0, 0.0
        reach = half * math.sqrt(2.0) + 1.0  # the cap corners stick out this far from the ends
        col_lo = max(0, int(math.floor(min(x0, x1) - reach)))
        col_hi = min(CANVAS_PX - 1, int(math.ceil(max(x0, x1) + reach)))
        row_lo = max(0, int(math.floor(min(y0, y1) - reach)))
        row_hi = min(CANVAS_PX - 1, int(math.ceil(max(y0, y1) + reach)))
        if col_lo > col_hi or row_lo > row_hi:
            return
        cols = np.arange(col_lo, col_hi + 1, dtype=np.float64)[np.newaxis, :] - x0
        rows = np.arange(row_lo, row_hi + 1, dtype=np.float64)[:, np.newaxis] - y0
        along = cols * ux + rows * uy
        across = rows * ux - cols * uy
        inside = (along >= -half) & (along < length + half) & (across >= -half) & (across < half)
        self.pixels[row_lo:row_hi + 1, col_lo:col_hi + 1][inside] = color
        self.version += 1
