"""Geometry the checks measure with: path lengths, circles and polygons from poses and from the canvas.

Pure numpy and PIL (no rospy), so that test/unit/ checks it in milliseconds.
"""
import math

import numpy
from PIL import Image

from course_checks.verdict import Verdict

WORLD_SIZE = 11.088889        # metres: turtlesim's world is a square of this side
PIXELS_PER_METRE = 45.0
PEN_COLOUR = (179, 184, 255)  # turtlesim's default pen
BACKGROUND_COLOUR = (69, 86, 255)


def path_length(points):
    """Length in metres of the polyline through (x, y) points."""
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(points, points[1:]))


def polygon(x, y, theta, side, corners):
    """Vertices of the regular polygon a turtle at (x, y, theta) drives turning left, start first."""
    turn = 2 * math.pi / corners
    vertices = [(x, y)]
    for i in range(corners - 1):
        x += side * math.cos(theta + i * turn)
        y += side * math.sin(theta + i * turn)
        vertices.append((x, y))
    return numpy.array(vertices)


def distances_to_polygon(points, vertices):
    """Distance from each point (N x 2) to the closed outline through the vertices."""
    points = numpy.asarray(points, dtype=float)
    best = numpy.full(len(points), numpy.inf)
    for start, end in zip(vertices, numpy.roll(vertices, -1, axis=0)):
        edge = end - start
        along = numpy.clip((points - start) @ edge / (edge @ edge), 0.0, 1.0)
        nearest = start + along[:, None] * edge
        best = numpy.minimum(best, numpy.hypot(*(points - nearest).T))
    return best


def closed_path(path, outline, tolerance):
    """The path ((x, y) rows, from its start) follows the closed outline (vertices, start first)
    and ends at its start, each within tolerance metres."""
    away = distances_to_polygon(path, outline).max()
    missed = math.hypot(path[-1][0] - outline[0][0], path[-1][1] - outline[0][1])
    return Verdict(away <= tolerance and missed <= tolerance, 'the path at most %.3f m off the outline, ending '
                   '%.3f m from the start' % (away, missed))


def fit_circle(points):
    """Least-squares circle through the points (N x 2): returns (centre_x, centre_y, radius)."""
    x, y = numpy.asarray(points, dtype=float).T
    # x^2 + y^2 = 2 a x + 2 b y + c  is linear in a, b, c, with radius^2 = c + a^2 + b^2.
    design = numpy.column_stack([2 * x, 2 * y, numpy.ones_like(x)])
    (a, b, c), *_ = numpy.linalg.lstsq(design, x * x + y * y, rcond=None)
    return a, b, math.sqrt(c + a * a + b * b)


def turning_spots(poses):
    """Where a turtle turned on the spot: the mean (x, y) of each run of poses (rows of x, y, theta,
    linear_velocity, angular_velocity) that rotate without moving forward."""
    spots, run = [], []
    for pose in poses:
        if pose[4] != 0.0 and pose[3] == 0.0:
            run.append(pose[:2])
        elif run:
            spots.append(numpy.mean(run, axis=0))
            run = []
    if run:
        spots.append(numpy.mean(run, axis=0))
    return numpy.array(spots)


def pen_points(png_path):
    """World coordinates (N x 2, metres) of the canvas pixels in the pen's colour (give or take a
    little blending at the edges of lines)."""
    pixels = numpy.asarray(Image.open(png_path).convert('RGB'), dtype=float)
    rows, columns = numpy.nonzero(numpy.linalg.norm(pixels - PEN_COLOUR, axis=2) < 40)
    height = pixels.shape[0]
    return numpy.column_stack([columns / PIXELS_PER_METRE, (height - 1 - rows) / PIXELS_PER_METRE])


def corners_from_sides(points, vertices, band=0.1, margin=0.2):
    """Where the drawn sides meet: a straight line is fitted to the points within `band` of each side
    of the polygon (leaving out `margin` at both ends, where the corners are), and each vertex is
    estimated as the crossing of the lines of the two sides that meet there."""
    points = numpy.asarray(points, dtype=float)
    lines = []
    for start, end in zip(vertices, numpy.roll(vertices, -1, axis=0)):
        edge = end - start
        length = math.hypot(*edge)
        direction = edge / length
        relative = points - start
        along = relative @ direction
        across = relative @ numpy.array([-direction[1], direction[0]])
        near = points[(numpy.abs(across) < band) & (along > margin) & (along < length - margin)]
        if len(near) < 2:
            raise AssertionError('nothing drawn along the side from %s to %s' % (start, end))
        centre = near.mean(axis=0)
        _, _, axes = numpy.linalg.svd(near - centre)
        lines.append((centre, axes[0]))
    estimates = []
    for (point_a, dir_a), (point_b, dir_b) in zip(lines[-1:] + lines[:-1], lines):
        # point_a + s dir_a = point_b + t dir_b
        s, _ = numpy.linalg.solve(numpy.column_stack([dir_a, -dir_b]), point_b - point_a)
        estimates.append(point_a + s * dir_a)
    return numpy.array(estimates)
