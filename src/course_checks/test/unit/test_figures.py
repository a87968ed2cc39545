"""The measuring tools of the rostests, checked on figures whose answer is known."""
import math

import numpy
import pytest
from PIL import Image, ImageDraw

from course_checks import figures


def test_path_length_adds_the_sides_of_the_polyline():
    assert figures.path_length([(0, 0), (3, 4), (3, 0)]) == pytest.approx(9.0)
    assert figures.path_length([(0, 0), (2, 0), (2, 2), (0, 2), (0, 0)]) == pytest.approx(8.0)
    assert figures.path_length([(1, 1)]) == 0.0
    assert figures.path_length([]) == 0.0


def test_polygon_square_and_triangle_from_one_one():
    square = figures.polygon(1, 1, 0, 3, 4)
    numpy.testing.assert_allclose(square, [(1, 1), (4, 1), (4, 4), (1, 4)], atol=1e-12)
    triangle = figures.polygon(1, 1, 0, 3, 3)
    numpy.testing.assert_allclose(triangle, [(1, 1), (4, 1), (2.5, 1 + 1.5 * math.sqrt(3))], atol=1e-12)


def test_distances_to_polygon():
    square = figures.polygon(0, 0, 0, 2, 4)
    points = [(1, 0), (1, 0.5), (3, 1), (-1, -1), (1, 1)]
    numpy.testing.assert_allclose(figures.distances_to_polygon(points, square),
                                  [0, 0.5, 1, math.sqrt(2), 1], atol=1e-12)


def test_fit_circle_recovers_centre_and_radius():
    angles = numpy.linspace(0, 2 * math.pi, 400, endpoint=False)
    points = numpy.column_stack([3 + 1.5 * numpy.cos(angles), 4 + 1.5 * numpy.sin(angles)])
    assert figures.fit_circle(points) == pytest.approx((3, 4, 1.5), abs=1e-9)


def test_turning_spots_are_the_runs_of_rotation_on_the_spot():
    poses = [(0, 0, 0, 1, 0), (1, 0, 0, 0, 1), (1.002, 0, 0.5, 0, 1), (1, 0, 1, 1, 0.2),
             (1, 1, 1.5, 0, -1), (1, 1, 1.5, 0, 0)]
    numpy.testing.assert_allclose(figures.turning_spots(poses), [(1.001, 0), (1, 1)])


def draw_canvas(path, vertices):
    """A 500 x 500 canvas in turtlesim's colours with the closed outline drawn 3 px wide."""
    image = Image.new('RGB', (500, 500), figures.BACKGROUND_COLOUR)
    pixels = [(x * figures.PIXELS_PER_METRE, 499 - y * figures.PIXELS_PER_METRE) for x, y in vertices]
    ImageDraw.Draw(image).line(pixels + pixels[:1], fill=figures.PEN_COLOUR, width=3)
    image.save(path)


def test_pen_points_are_where_the_pen_drew(tmp_path):
    square = figures.polygon(1, 1, 0, 3, 4)
    draw_canvas(tmp_path / 'square.png', square)
    points = figures.pen_points(tmp_path / 'square.png')
    assert len(points) > 3 * 4 * 3 * figures.PIXELS_PER_METRE * 0.9
    assert figures.distances_to_polygon(points, square).max() < 2 / figures.PIXELS_PER_METRE


@pytest.mark.parametrize('corners', [3, 4])
def test_corners_from_sides_find_the_drawn_corners(tmp_path, corners):
    ideal = figures.polygon(1, 1, 0, 3, corners)
    draw_canvas(tmp_path / 'ideal.png', ideal)
    found = figures.corners_from_sides(figures.pen_points(tmp_path / 'ideal.png'), ideal)
    assert numpy.hypot(*(found - ideal).T).max() < 1.5 / figures.PIXELS_PER_METRE


def test_corners_from_sides_see_a_corner_that_is_off(tmp_path):
    ideal = figures.polygon(1, 1, 0, 3, 4)
    bent = ideal.copy()
    bent[2] += (0.08, 0.0)
    draw_canvas(tmp_path / 'bent.png', bent)
    found = figures.corners_from_sides(figures.pen_points(tmp_path / 'bent.png'), ideal)
    errors = numpy.hypot(*(found - ideal).T)
    assert errors[2] > 0.05
    assert errors[0] < 0.02


def test_corners_from_sides_report_a_missing_side():
    ideal = figures.polygon(1, 1, 0, 3, 3)
    only_first_side = numpy.column_stack([numpy.linspace(1, 4, 100), numpy.ones(100)])
    with pytest.raises(AssertionError, match='nothing drawn'):
        figures.corners_from_sides(only_first_side, ideal)


def test_a_closed_path_follows_the_outline_back_to_its_start():
    square = figures.polygon(1.0, 1.0, 0.0, 2.0, 4)
    around = numpy.concatenate([numpy.linspace(a, b, 50) for a, b in zip(square, numpy.roll(square, -1, axis=0))])
    closed = figures.closed_path(around, square, 0.05)
    assert closed.passed and closed.reason == 'the path at most 0.000 m off the outline, ending 0.000 m from the start'
    short = figures.closed_path(around[:-20], square, 0.05)
    assert not short.passed and 'ending 0.8' in short.reason
    assert not figures.closed_path(around + (0.1, 0.0), square, 0.05).passed
