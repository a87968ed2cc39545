"""Line drawing on the path canvas, and the picture with the turtle icons on top."""
import math

import numpy as np

from turtlesim.canvas import Canvas
from turtlesim.picture import compose, ppm_bytes
from turtlesim.world import DEFAULT_BACKGROUND, World

RED = (255, 0, 0)


class SilentLog:
    def info(self, text):
        pass

    warning = info


def painted(canvas):
    rows, cols = np.nonzero((canvas.pixels == RED).all(axis=2))
    return set(zip(cols.tolist(), rows.tolist()))


def test_a_point_paints_a_width_by_width_square():
    canvas = Canvas(DEFAULT_BACKGROUND)
    canvas.draw_line(100.0, 200.0, 100.0, 200.0, RED, 3)
    assert painted(canvas) == {(col, row) for col in (99, 100, 101) for row in (199, 200, 201)}


def test_a_diagonal_line_has_no_gaps():
    canvas = Canvas(DEFAULT_BACKGROUND)
    canvas.draw_line(10.0, 10.0, 110.0, 60.0, RED, 1)
    pixels = painted(canvas)
    assert all(any((col, row) in pixels for row in range(500)) for col in range(10, 111))
    assert not any((col, row) in pixels for col, row in [(5, 5), (120, 60), (60, 10)])


def test_a_line_from_far_outside_is_clipped_to_what_is_visible():
    canvas = Canvas(DEFAULT_BACKGROUND)
    canvas.draw_line(-1e30, 250.0, 1e30, 250.0, RED, 1)
    assert painted(canvas) == {(col, 250) for col in range(500)}
    canvas.draw_line(-1e30, -1e30, -1e29, -1e30, (0, 255, 0), 9)  # entirely outside
    assert ((canvas.pixels == (0, 255, 0)).all(axis=2)).sum() == 0


def test_drawing_changes_the_version():
    canvas = Canvas(DEFAULT_BACKGROUND)
    before = canvas.version
    canvas.draw_line(1.0, 1.0, 5.0, 5.0, RED, 2)
    assert canvas.version > before


def test_turtle_icons_sit_on_a_copy_of_the_path():
    world = World(SilentLog())
    world.spawn('corner', 0.0, 0.0, math.pi / 4)
    path = world.canvas.pixels.copy()
    image = compose(world.canvas.pixels, world.turtles())
    assert (world.canvas.pixels == path).all()  # the colour sensor never sees a turtle
    changed = np.nonzero((image != path).any(axis=2))
    rows, cols = changed
    assert 150 < len(rows) < 41 * 41
    # turtle1 in the centre (249.5 px) and 'corner' at the bottom-left pixel (0, 499)
    centre = (abs(rows - 249.5) <= 20) & (abs(cols - 249.5) <= 20)
    corner = (rows >= 479) & (cols <= 20)
    assert (centre | corner).all() and centre.any() and corner.any()


def test_the_icon_turns_with_the_turtle():
    world = World(SilentLog())
    east = compose(world.canvas.pixels, world.turtles())
    world.teleport_absolute('turtle1', world.turtle('turtle1').x, world.turtle('turtle1').y, math.pi / 2)
    world.tick(0.0)
    north = compose(world.canvas.pixels, world.turtles())
    background = np.array(DEFAULT_BACKGROUND)
    east_cols = np.nonzero((east != background).any(axis=2))[1]
    north_rows = np.nonzero((north != background).any(axis=2))[0]
    # the head sticks out further than the tail: east of the centre facing east, above it facing north
    assert east_cols.max() - 249.5 > 249.5 - east_cols.min()
    assert 249.5 - north_rows.min() > north_rows.max() - 249.5


def test_ppm_bytes():
    image = np.zeros((2, 3, 3), dtype=np.uint8)
    image[1, 2] = (1, 2, 3)
    assert ppm_bytes(image) == b'P6 3 2 255\n' + bytes(15) + bytes((1, 2, 3))
