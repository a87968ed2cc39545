"""Vectorised 2D geometry on numpy arrays: ray casting and body overlap tests.

Obstacles are described by their outlines: `segments` is an (N, 4) array of x0, y0, x1, y1 and
`circles` an (M, 3) array of cx, cy, radius. Segments run counterclockwise around the solid they
bound (the solid is on their left), so a ray knows whether it enters or leaves a solid.
"""
import numpy as np

NO_SEGMENTS = np.zeros((0, 4))
NO_CIRCLES = np.zeros((0, 3))


def _squared_distances(segments, x, y):
    """Squared distance from (x, y) to each segment."""
    ax, ay = segments[:, 0] - x, segments[:, 1] - y
    ex, ey = segments[:, 2] - segments[:, 0], segments[:, 3] - segments[:, 1]
    # The tiny term keeps a zero-length segment at along = 0 instead of 0 / 0.
    along = np.minimum(np.maximum(-(ax * ex + ay * ey) / (ex * ex + ey * ey + 1e-300), 0.0), 1.0)
    nearest_x, nearest_y = ax + along * ex, ay + along * ey
    return nearest_x * nearest_x + nearest_y * nearest_y


def _segments_near(segments, x, y, radius):
    """The segments that come within `radius` of point (x, y)."""
    if not len(segments):
        return segments
    return segments[_squared_distances(segments, x, y) <= radius * radius]


def _circles_near(circles, x, y, radius):
    """The circles that come within `radius` of point (x, y)."""
    if not len(circles):
        return circles
    reach = radius + circles[:, 2]
    return circles[(circles[:, 0] - x) ** 2 + (circles[:, 1] - y) ** 2 <= reach * reach]


def clearance(x, y, segments=NO_SEGMENTS, circles=NO_CIRCLES):
    """Distance from (x, y) to the nearest outline (inf when there is none)."""
    nearest = np.inf
    if len(segments):
        nearest = np.sqrt(_squared_distances(segments, x, y).min())
    if len(circles):
        centres = np.hypot(circles[:, 0] - x, circles[:, 1] - y) - circles[:, 2]
        nearest = min(nearest, max(centres.min(), 0.0))
    return float(nearest)


def cast_rays(x, y, angles, near, far, segments=NO_SEGMENTS, circles=NO_CIRCLES):
    """Distance along each ray from (x, y) at `angles` to the first surface it enters between
    `near` and `far`; +inf where it enters none.

    The ray starts at `near`, as a laser's does: a surface nearer than that is not seen, and a ray
    that starts inside a solid does not see that solid from within (surfaces are seen from outside
    only, like Gazebo's one-sided meshes). A ray touching a segment end or grazing a circle hits;
    a ray running along a segment does not.
    """
    cos_a, sin_a = np.cos(angles), np.sin(angles)
    best = np.full(cos_a.shape, np.inf)
    if len(segments):
        ax, ay = segments[:, 0] - x, segments[:, 1] - y
        ex, ey = segments[:, 2] - segments[:, 0], segments[:, 3] - segments[:, 1]
        # Ray t*d meets segment a + u*e where t = (a x e) / (d x e) and u = (a x d) / (d x e).
        # A ray enters a solid where d x e < 0 (it comes from the right of the segment, outside),
        # which with t > 0 needs a x e < 0: segments facing away are dropped first, with those
        # out of reach.
        a_cross_e = ax * ey - ay * ex
        facing = (a_cross_e < 0) & (_squared_distances(segments, x, y) <= far * far)
        ax, ay, ex, ey = ax[facing], ay[facing], ex[facing], ey[facing]
        a_cross_e = a_cross_e[facing]
        if len(ax):
            directions = np.stack([cos_a, sin_a], axis=1)
            products = directions @ np.array([np.concatenate([ey, ay]), np.concatenate([-ex, -ax])])
            n = len(ax)
            d_cross_e, a_cross_d = products[:, :n], -products[:, n:]
            with np.errstate(divide='ignore', invalid='ignore'):
                t = a_cross_e / d_cross_e
                u = a_cross_d / d_cross_e
            hit = (d_cross_e < 0) & (u >= 0.0) & (u <= 1.0) & (t >= near) & (t <= far)
            best = np.where(hit, t, np.inf).min(axis=1)
    circles = _circles_near(circles, x, y, far)
    if len(circles):
        mx, my = x - circles[:, 0], y - circles[:, 1]
        b = np.outer(cos_a, mx) + np.outer(sin_a, my)
        discriminant = b * b - (mx * mx + my * my - circles[:, 2] ** 2)
        t = -b - np.sqrt(np.maximum(discriminant, 0.0))  # where the ray enters the disc
        hit = (discriminant >= 0.0) & (t >= near) & (t <= far)
        best = np.minimum(best, np.where(hit, t, np.inf).min(axis=1))
    return best


def boxes_overlap(poses, box, segments=NO_SEGMENTS, circles=NO_CIRCLES):
    """For each pose, whether a rectangle carried by the pose overlaps an outline.

    poses: arrays (x, y, yaw) of one shape; box: (centre x in the pose frame, half length, half
    width). A segment overlaps when any part of it lies in the rectangle (crossing or inside),
    a circle when its disc reaches the rectangle. Returns a bool array of the poses' shape.
    """
    px, py, pyaw = (np.atleast_1d(np.asarray(v, dtype=float)) for v in poses)
    centre_x, half_length, half_width = box
    cos_y, sin_y = np.cos(pyaw)[:, None], np.sin(pyaw)[:, None]
    cx, cy = px[:, None] + centre_x * cos_y, py[:, None] + centre_x * sin_y
    overlap = np.zeros(px.shape, dtype=bool)

    def to_box(wx, wy):
        dx, dy = wx - cx, wy - cy
        return dx * cos_y + dy * sin_y, -dx * sin_y + dy * cos_y

    if len(segments):
        # Liang-Barsky: clip each segment against the box; it overlaps when something remains.
        x0, y0 = to_box(segments[:, 0], segments[:, 1])
        x1, y1 = to_box(segments[:, 2], segments[:, 3])
        low, high = np.zeros(x0.shape), np.ones(x0.shape)
        with np.errstate(divide='ignore', invalid='ignore'):
            for start, delta, half in ((x0, x1 - x0, half_length), (y0, y1 - y0, half_width)):
                enter, leave = (-half - start) / delta, (half - start) / delta
                parallel = delta == 0
                # A segment parallel to this side lies wholly inside the slab or wholly outside.
                low = np.where(parallel, np.where(np.abs(start) <= half, low, np.inf),
                               np.fmax(low, np.minimum(enter, leave)))
                high = np.where(parallel, high, np.fmin(high, np.maximum(enter, leave)))
        overlap |= (low <= high).any(axis=1)
    if len(circles):
        bx, by = to_box(circles[:, 0], circles[:, 1])
        gap_x = np.maximum(np.abs(bx) - half_length, 0.0)
        gap_y = np.maximum(np.abs(by) - half_width, 0.0)
        overlap |= (gap_x * gap_x + gap_y * gap_y <= circles[:, 2] ** 2).any(axis=1)
    return overlap


def box_outline(x, y, yaw, box):
    """The four sides of the rectangle `box` carried by pose (x, y, yaw): a (4, 4) segment array
    running counterclockwise."""
    centre_x, half_length, half_width = box
    local = np.array([[half_length, half_width], [-half_length, half_width],
                      [-half_length, -half_width], [half_length, -half_width]])
    c, s = np.cos(yaw), np.sin(yaw)
    corners_x = x + (centre_x + local[:, 0]) * c - local[:, 1] * s
    corners_y = y + (centre_x + local[:, 0]) * s + local[:, 1] * c
    return np.stack([corners_x, corners_y, np.roll(corners_x, -1), np.roll(corners_y, -1)], axis=1)


def nearby(segments, circles, x, y, radius):
    """The segments and circles that come within `radius` of (x, y): a cheap pre-filter."""
    return _segments_near(segments, x, y, radius), _circles_near(circles, x, y, radius)
