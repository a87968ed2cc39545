"""Worlds: obstacles described in our own YAML files (worlds/*.yaml), turned into outlines.

A world file has a `name` and a list of `obstacles`, each a mapping with a `type`:
  circle:          center [x, y], radius
  box:             center [x, y], size [length, width], yaw (optional, rad)
  polygon:         points [[x, y], ...] (the outline of one solid, closed automatically)
  regular_polygon: center [x, y], sides, circumradius, rotation (optional, rad; 0 puts a corner
                   on the +x axis)
  ring:            a regular polygon wall: center, sides, circumradius (of the inner outline),
                   thickness (measured square to the sides), rotation
"""
import math
import os

import numpy as np
import yaml

WORLDS_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'worlds')


class WorldError(ValueError):
    """A world that cannot be loaded: missing file, bad YAML, bad obstacle."""


def _closed_outline(points, solid_inside=True):
    """Segments joining consecutive points, the last back to the first, running counterclockwise
    around the solid: around the points when solid_inside, clockwise (solid outside) for a hole."""
    points = np.asarray(points, dtype=float)
    following = np.roll(points, -1, axis=0)
    doubled_area = np.sum(points[:, 0] * following[:, 1] - following[:, 0] * points[:, 1])
    if (doubled_area > 0) != solid_inside:
        points = points[::-1]
        following = np.roll(points, -1, axis=0)
    return np.hstack([points, following])


def _regular_polygon(center, sides, circumradius, rotation):
    angles = rotation + 2 * math.pi * np.arange(sides) / sides
    return np.stack([center[0] + circumradius * np.cos(angles),
                     center[1] + circumradius * np.sin(angles)], axis=1)


class World:
    """Static obstacles: outlines for ray casting and collisions, filled shapes for drawing.

    `shapes` lists what to draw, in order: ('polygon', points) filled, ('hole', points) cut out
    again (the inside of a ring), ('circle', (cx, cy, r)).
    """

    def __init__(self, name, obstacles=()):
        self.name = name
        self.shapes = []
        segments, circles = [], []
        for index, obstacle in enumerate(obstacles):
            try:
                new_segments, new_circles, shapes = self._parse(obstacle)
            except (KeyError, TypeError, ValueError) as err:
                raise WorldError('world %s, obstacle %d (%r): %s' % (name, index + 1, obstacle,
                                                                      _describe(err))) from None
            segments.extend(new_segments)
            circles.extend(new_circles)
            self.shapes.extend(shapes)
        self.segments = np.vstack(segments) if segments else np.zeros((0, 4))
        self.circles = np.array(circles, dtype=float).reshape(-1, 3)

    @staticmethod
    def _parse(obstacle):
        kind = obstacle['type']
        if kind == 'circle':
            cx, cy = _point(obstacle['center'])
            radius = _positive(obstacle['radius'], 'radius')
            return [], [(cx, cy, radius)], [('circle', (cx, cy, radius))]
        if kind == 'box':
            cx, cy = _point(obstacle['center'])
            length, width = (_positive(v, 'size') for v in obstacle['size'])
            yaw = float(obstacle.get('yaw', 0.0))
            c, s = math.cos(yaw), math.sin(yaw)
            corners = [(cx + c * dx - s * dy, cy + s * dx + c * dy)
                       for dx, dy in ((length / 2, width / 2), (-length / 2, width / 2),
                                      (-length / 2, -width / 2), (length / 2, -width / 2))]
            return [_closed_outline(corners)], [], [('polygon', np.array(corners))]
        if kind == 'polygon':
            points = np.array([_point(p) for p in obstacle['points']])
            if len(points) < 3:
                raise ValueError('a polygon needs at least 3 points')
            return [_closed_outline(points)], [], [('polygon', points)]
        if kind in ('regular_polygon', 'ring'):
            center = _point(obstacle['center'])
            sides = int(obstacle['sides'])
            if sides < 3:
                raise ValueError('sides must be at least 3')
            circumradius = _positive(obstacle['circumradius'], 'circumradius')
            rotation = float(obstacle.get('rotation', 0.0))
            inner = _regular_polygon(center, sides, circumradius, rotation)
            if kind == 'regular_polygon':
                return [_closed_outline(inner)], [], [('polygon', inner)]
            thickness = _positive(obstacle['thickness'], 'thickness')
            outer = _regular_polygon(center, sides,
                                     circumradius + thickness / math.cos(math.pi / sides), rotation)
            return ([_closed_outline(inner, solid_inside=False), _closed_outline(outer)], [],
                    [('polygon', outer), ('hole', inner)])
        raise ValueError('unknown obstacle type %r (circle, box, polygon, regular_polygon, ring)'
                         % (kind,))

    def bounds(self):
        """(xmin, ymin, xmax, ymax) of every obstacle, or None for an empty world."""
        xs, ys = [], []
        if len(self.segments):
            xs += [self.segments[:, 0], self.segments[:, 2]]
            ys += [self.segments[:, 1], self.segments[:, 3]]
        if len(self.circles):
            xs += [self.circles[:, 0] - self.circles[:, 2], self.circles[:, 0] + self.circles[:, 2]]
            ys += [self.circles[:, 1] - self.circles[:, 2], self.circles[:, 1] + self.circles[:, 2]]
        if not xs:
            return None
        xs, ys = np.concatenate(xs), np.concatenate(ys)
        return float(xs.min()), float(ys.min()), float(xs.max()), float(ys.max())


def _describe(err):
    if isinstance(err, KeyError):
        return 'missing key %s' % err
    return str(err)


def _point(value):
    x, y = value
    return float(x), float(y)


def _positive(value, what):
    value = float(value)
    if not value > 0:
        raise ValueError('%s must be positive, got %r' % (what, value))
    return value


def available_worlds(worlds_dir=WORLDS_DIR):
    """Names of the worlds in worlds_dir (by default the package's worlds/)."""
    return sorted(name[:-5] for name in os.listdir(worlds_dir) if name.endswith('.yaml'))


def load_world(name_or_path, worlds_dir=WORLDS_DIR):
    """The World of a world name in worlds_dir (e.g. 'turtlebot3_world') or of a YAML file path."""
    path = str(name_or_path)
    if not os.path.isfile(path):
        path = os.path.join(worlds_dir, '%s.yaml' % name_or_path)
    if not os.path.isfile(path):
        raise WorldError('no world %r: give a YAML file or one of %s'
                         % (name_or_path, ', '.join(available_worlds(worlds_dir))))
    try:
        with open(path) as stream:
            content = yaml.safe_load(stream) or {}
    except (OSError, yaml.YAMLError) as err:
        raise WorldError('cannot read world file %s: %s' % (path, err)) from None
    if not isinstance(content, dict) or not isinstance(content.get('obstacles', []), list):
        raise WorldError('world file %s: expected a mapping with a list `obstacles`' % path)
    name = content.get('name', os.path.splitext(os.path.basename(path))[0])
    return World(name, content.get('obstacles') or [])
