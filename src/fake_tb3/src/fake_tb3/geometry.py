"""Vectorised 2D geometry on numpy arrays: ray casting and body overlap tests.

Obstacles are described by their outlines: `segments` is an (N, 4) array of x0, y0, x1, y1 and
`circles` an (M, 3) array of cx, cy, radius. Segments run counterclockwise around the solid they
bound (the solid is on their left), so a ray knows whether it enters or leaves a solid.
"""
import numpy as np

NO_SEGMENTS = np.zeros((0, 4))
NO_CIRCLES = np.zeros((0, 3))


def _squared_distances(segments, x, y, ex=None, ey=None):
    """Squared distance from (x, y) to each segment (ex, ey: its vectors, if made already)."""
    ax, ay = segments[:, 0] - x, segments[:, 1] - y
    if ex is None:
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
    return cast_scans(np.array([[x, y, 0.0]]), angles, near, far, segments, circles)[0]


def cast_scans(poses, angles, near, far, segments=NO_SEGMENTS, circles=NO_CIRCLES, owners=None):
    """cast_rays from several origins at once: ranges (len(poses), len(angles)), row i from
    (x, y) of poses[i] = (x, y, yaw) along yaw + angles. owners: for each segment the index of
    the pose that does not see it (the laser's own robot), or -1.

    Each ray is tested only against the outlines it can reach: those within `far` that face its
    origin and whose angle, seen from there, spans its direction (with a margin far wider than
    rounding). A ray left out could not have hit, so the ranges are those of testing every ray
    against every outline, beam by beam; the work grows with the rays that pass near an outline,
    not with rays times outlines (30 robots seeing each other: 30 x 29 bodies, 360 beams each).
    """
    poses = np.asarray(poses, dtype=float).reshape(-1, 3)
    angles = np.asarray(angles, dtype=float)
    if len(poses) == 1:
        return _cast_every_ray(poses[0], angles, near, far, segments, circles, owners)[None, :]
    count, beams = len(poses), len(angles)
    px, py = poses[:, 0:1], poses[:, 1:2]
    directions = angles + poses[:, 2:3]  # as a laser adds its yaw to its beam angles
    cos_a, sin_a = np.cos(directions).ravel(), np.sin(directions).ravel()
    # The beams by their angle from the yaw, in [0, 2 pi): where an outline's span falls.
    relative = np.mod(angles, 2 * np.pi)
    beam_order = np.argsort(relative, kind='stable')
    rays = _RaySpans(relative[beam_order], beam_order, poses[:, 2], beams)
    ray_ids, distances = [], []
    if len(segments):
        ax, ay = segments[:, 0] - px, segments[:, 1] - py  # (poses, segments)
        ex, ey = segments[:, 2] - segments[:, 0], segments[:, 3] - segments[:, 1]
        # Ray t*d meets segment a + u*e where t = (a x e) / (d x e) and u = (a x d) / (d x e).
        # A ray enters a solid where d x e < 0 (it comes from the right of the segment, outside),
        # which with t > 0 needs a x e < 0: segments facing away are dropped first, with those
        # out of reach and each laser's own body.
        a_cross_e = ax * ey - ay * ex
        keep = (a_cross_e < 0) & (_squared_distances(segments, px, py) <= far * far)
        if owners is not None:
            keep &= np.asarray(owners)[None, :] != np.arange(count)[:, None]
        pose_of, segment_of = np.nonzero(keep)
        ax, ay, a_cross_e = ax[keep], ay[keep], a_cross_e[keep]
        ex, ey = ex[segment_of], ey[segment_of]
        # Seen from the origin the segment spans, counterclockwise, from its end a + e to its
        # start a (facing: a x (a + e) < 0), less than half a turn.
        bx, by = ax + ex, ay + ey
        span = np.arctan2(-a_cross_e, ax * bx + ay * by)
        pair, ray = rays.within(pose_of, np.arctan2(by, bx), span)
        c, s = cos_a[ray], sin_a[ray]
        d_cross_e = c * ey[pair] - s * ex[pair]
        a_cross_d = s * ax[pair] - c * ay[pair]
        with np.errstate(divide='ignore', invalid='ignore'):
            t = a_cross_e[pair] / d_cross_e
            u = a_cross_d / d_cross_e
        hit = (d_cross_e < 0) & (u >= 0.0) & (u <= 1.0) & (t >= near) & (t <= far)
        ray_ids.append(ray[hit])
        distances.append(t[hit])
    if len(circles):
        mx, my = px - circles[:, 0], py - circles[:, 1]  # (poses, circles)
        centre_distance = np.hypot(mx, my)
        reach = far + circles[:, 2]
        pose_of, circle_of = np.nonzero(mx * mx + my * my <= reach * reach)
        mx, my, centre_distance = (v[pose_of, circle_of] for v in (mx, my, centre_distance))
        radius = circles[circle_of, 2]
        # A disc spans 2 asin(r / d) around its centre's direction; all around from inside it.
        outside = centre_distance > radius
        half = np.arcsin(np.where(outside, radius / np.where(outside, centre_distance, 1.0), 1.0))
        span = np.where(outside, 2 * half, 2 * np.pi)
        pair, ray = rays.within(pose_of, np.arctan2(-my, -mx) - half, span)
        mx, my = mx[pair], my[pair]
        b = cos_a[ray] * mx + sin_a[ray] * my
        discriminant = b * b - (mx * mx + my * my - radius[pair] ** 2)
        t = -b - np.sqrt(np.maximum(discriminant, 0.0))  # where the ray enters the disc
        hit = (discriminant >= 0.0) & (t >= near) & (t <= far)
        ray_ids.append(ray[hit])
        distances.append(t[hit])
    best = np.full(count * beams, np.inf)
    if ray_ids:
        ray_ids, distances = np.concatenate(ray_ids), np.concatenate(distances)
        order = np.lexsort((distances, ray_ids))  # by ray, nearest first
        ray_ids, distances = ray_ids[order], distances[order]
        first = np.ones(len(ray_ids), dtype=bool)
        first[1:] = ray_ids[1:] != ray_ids[:-1]
        best[ray_ids[first]] = distances[first]
    return best.reshape(count, beams)


def _cast_every_ray(pose, angles, near, far, segments, circles, owners):
    """cast_scans from one origin: every ray against every outline within reach that faces it, in
    arrays (outlines, beams). With one origin this costs less than finding each outline's rays
    (the arithmetic of each ray and outline is the same, so are the ranges, to the last bit)."""
    px, py, yaw = pose.tolist()
    directions = angles + yaw
    cos_a, sin_a = np.cos(directions), np.sin(directions)
    best = np.full(len(angles), np.inf)
    if len(segments):  # arrays (outlines, beams) from here on
        ax, ay = segments[:, 0] - px, segments[:, 1] - py
        ex, ey = segments[:, 2] - segments[:, 0], segments[:, 3] - segments[:, 1]
        a_cross_e = ax * ey - ay * ex
        keep = (a_cross_e < 0) & (_squared_distances(segments, px, py, ex, ey) <= far * far)
        if owners is not None:
            keep &= np.asarray(owners) != 0
        ax, ay, a_cross_e = ax[keep, None], ay[keep, None], a_cross_e[keep, None]
        ex, ey = ex[keep, None], ey[keep, None]
        d_cross_e = cos_a * ey - sin_a * ex
        a_cross_d = sin_a * ax - cos_a * ay
        with np.errstate(divide='ignore', invalid='ignore'):  # rays along a segment: unused
            t = a_cross_e / d_cross_e
            u = a_cross_d / d_cross_e
        # As a x e < 0, t >= near > 0 holds only where d x e < 0: the test of entering is in it.
        hit = (u >= 0.0) & (u <= 1.0) & (t >= near) & (t <= far)
        best = np.where(hit, t, np.inf).min(axis=0, initial=np.inf)
    if len(circles):
        mx, my = px - circles[:, 0], py - circles[:, 1]
        reach = far + circles[:, 2]
        within = mx * mx + my * my <= reach * reach
        mx, my, radius = mx[within, None], my[within, None], circles[within, 2, None]
        b = cos_a * mx + sin_a * my
        discriminant = b * b - (mx * mx + my * my - radius ** 2)
        t = -b - np.sqrt(np.maximum(discriminant, 0.0))  # where the ray enters the disc
        hit = (discriminant >= 0.0) & (t >= near) & (t <= far)
        np.minimum(best, np.where(hit, t, np.inf).min(axis=0, initial=np.inf), out=best)
    return best


# Radians added on each side of an outline's span: far more than the rounding of the angles,
# far less than a beam's spacing matters (a wider span only tests more rays).
SPAN_MARGIN = 1e-6


class _RaySpans:
    """Finds the rays of each origin whose direction lies in a span of angles."""

    def __init__(self, sorted_angles, beam_order, yaws, beams):
        self._sorted, self._order, self._yaws, self._beams = (sorted_angles, beam_order, yaws,
                                                              beams)

    def within(self, pose_of, start, span):
        """(pair, ray): for each pair k (origin pose_of[k], span of angles from start[k],
        counterclockwise, span[k] < 2 pi or 2 pi for all around) the flat index, origin * beams
        + beam, of each ray whose direction lies within it."""
        two_pi = 2 * np.pi
        first_angle = np.mod(start - self._yaws[pose_of] - SPAN_MARGIN, two_pi)
        last_angle = first_angle + span + 2 * SPAN_MARGIN
        whole = span >= two_pi
        first = np.where(whole, 0, np.searchsorted(self._sorted, first_angle, 'left'))
        last = np.where(whole, self._beams, np.searchsorted(self._sorted, last_angle, 'right'))
        # Past 2 pi the span goes on from angle 0.
        wrapped = np.where(whole, 0, np.searchsorted(self._sorted, last_angle - two_pi, 'right'))
        pairs = np.arange(len(pose_of))
        pair = np.concatenate([pairs, pairs])
        low = np.concatenate([first, np.zeros_like(wrapped)])
        counts = np.concatenate([last - first, wrapped])
        pair = np.repeat(pair, counts)
        position = (np.arange(len(pair)) + np.repeat(low - (np.cumsum(counts) - counts), counts))
        return pair, pose_of[pair] * self._beams + self._order[position]


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
    return box_outlines(np.array([[x, y, yaw]]), np.array([box]))[0]


# Corners of a box counterclockwise, as signs of its half length and half width.
_CORNER_SIGNS = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])


def box_outlines(poses, boxes):
    """box_outline of many: poses (N, 3) x, y, yaw, boxes (N, 3) as `box`; an (N, 4, 4) array."""
    poses, boxes = np.asarray(poses, dtype=float), np.asarray(boxes, dtype=float)
    local_x = boxes[:, 0:1] + _CORNER_SIGNS[:, 0] * boxes[:, 1:2]
    local_y = _CORNER_SIGNS[:, 1] * boxes[:, 2:3]
    # numpy's sin of a strided column may differ in the last bit with where the column lies in
    # memory: a contiguous copy makes the outlines the same whatever the memory holds.
    yaws = np.ascontiguousarray(poses[:, 2:3])
    c, s = np.cos(yaws), np.sin(yaws)
    corners_x = poses[:, 0:1] + local_x * c - local_y * s
    corners_y = poses[:, 1:2] + local_x * s + local_y * c
    following = [1, 2, 3, 0]
    return np.stack([corners_x, corners_y, corners_x[:, following], corners_y[:, following]],
                    axis=2)


def nearby(segments, circles, x, y, radius):
    """The segments and circles that come within `radius` of (x, y): a cheap pre-filter."""
    return _segments_near(segments, x, y, radius), _circles_near(circles, x, y, radius)
