"""What the window shows: the path canvas with the turtles drawn on top, and ways to save it.

The turtle icon is drawn here from a few ellipses and circles (head, four legs, tail, a shell with
a lighter centre), rotated to the turtle's heading; no image files are involved.
"""
import math

import numpy as np

from turtlesim.world import PX_PER_METER, pixel_index

ICON_RADIUS = 20  # pixels: the icon fits in a 41x41 box around the turtle's position

# (shell, shell centre, skin) for each icon style
_ICON_PALETTES = (
    ((34, 110, 52), (92, 170, 84), (150, 200, 110)),
    ((120, 80, 40), (190, 140, 70), (170, 200, 120)),
    ((30, 90, 110), (80, 160, 170), (160, 210, 140)),
    ((90, 100, 30), (170, 180, 60), (200, 190, 120)),
    ((70, 60, 110), (140, 120, 180), (150, 200, 130)),
    ((130, 50, 40), (210, 110, 80), (170, 210, 120)),
)
_EYE = (20, 20, 20)

# Shapes in the turtle's frame (pixels, heading along +u, v to its left), painted in this order.
# Each entry: (kind, centre u, centre v, radius u, radius v, palette index or colour)
_ICON_SHAPES = (
    ('ellipse', 7.0, 9.0, 3.5, 3.5, 2),
    ('ellipse', 7.0, -9.0, 3.5, 3.5, 2),
    ('ellipse', -8.0, 9.0, 3.5, 3.5, 2),
    ('ellipse', -8.0, -9.0, 3.5, 3.5, 2),
    ('ellipse', -14.0, 0.0, 2.5, 2.0, 2),
    ('ellipse', 13.5, 0.0, 5.0, 4.0, 2),
    ('ellipse', -1.0, 0.0, 12.0, 9.5, 0),
    ('ellipse', -1.0, 0.0, 7.5, 5.5, 1),
    ('ellipse', 15.5, 2.0, 1.0, 1.0, _EYE),
    ('ellipse', 15.5, -2.0, 1.0, 1.0, _EYE),
)


def _paint_turtle(image, turtle):
    centre_col, centre_row = pixel_index(turtle.x), pixel_index(turtle.qt_y)
    col_lo, col_hi = max(0, centre_col - ICON_RADIUS), min(image.shape[1] - 1, centre_col + ICON_RADIUS)
    row_lo, row_hi = max(0, centre_row - ICON_RADIUS), min(image.shape[0] - 1, centre_row + ICON_RADIUS)
    dx = np.arange(col_lo, col_hi + 1, dtype=np.float64)[np.newaxis, :] - turtle.x * PX_PER_METER
    dy = np.arange(row_lo, row_hi + 1, dtype=np.float64)[:, np.newaxis] - turtle.qt_y * PX_PER_METER
    cos, sin = math.cos(turtle.theta), math.sin(turtle.theta)
    # Image rows grow downwards while theta turns counter-clockwise in the world (y up).
    along = dx * cos - dy * sin
    left = -dx * sin - dy * cos
    palette = _ICON_PALETTES[turtle.icon % len(_ICON_PALETTES)]
    patch = image[row_lo:row_hi + 1, col_lo:col_hi + 1]
    for _, u, v, radius_u, radius_v, colour in _ICON_SHAPES:
        inside = ((along - u) / radius_u) ** 2 + ((left - v) / radius_v) ** 2 <= 1.0
        patch[inside] = palette[colour] if isinstance(colour, int) else colour


def compose(pixels, turtles):
    """A new RGB array: the path pixels with every turtle's icon on top (turtles in draw order)."""
    image = pixels.copy()
    for turtle in turtles:
        _paint_turtle(image, turtle)
    return image


def save_png(image, path):
    """Write an RGB array as a PNG file."""
    from PIL import Image  # only needed when a picture is saved
    Image.fromarray(image, 'RGB').save(path, format='PNG')


def ppm_bytes(image):
    """An RGB array as binary PPM, the format a Tk PhotoImage reads without extra libraries."""
    height, width = image.shape[:2]
    return b'P6 %d %d 255\n' % (width, height) + image.tobytes()
