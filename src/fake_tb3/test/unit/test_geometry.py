"""Ray casting and body overlap against cases solved by hand."""
import math

import numpy as np
import pytest

from fake_tb3.geometry import box_outline, box_outlines, boxes_overlap, cast_rays, cast_scans
from fake_tb3.world import World, load_world

NEAR, FAR = 0.12, 3.5


def outlines(*obstacles):
    world = World('test', obstacles)
    return world.segments, world.circles


WALL_AT_2 = outlines({'type': 'box', 'center': [2.05, 0.0], 'size': [0.1, 4.0]})


def test_wall_straight_ahead_and_at_an_angle():
    segments, circles = WALL_AT_2
    ranges = cast_rays(0.0, 0.0, np.radians([0.0, 30.0, 45.0, 180.0]), NEAR, FAR, segments, circles)
    # The near face is x = 2.0: a beam at angle a reaches it after 2 / cos(a).
    assert ranges[0] == pytest.approx(2.0)
    assert ranges[1] == pytest.approx(2.0 / math.cos(math.radians(30)))
    assert ranges[2] == pytest.approx(2.0 * math.sqrt(2))
    assert ranges[3] == math.inf  # nothing behind


def test_beyond_far_is_inf_and_far_itself_is_seen():
    segments, circles = outlines({'type': 'box', 'center': [2.05, 0.0], 'size': [0.1, 20.0]})
    # At 55 degrees the face is 2/cos(55) = 3.487 m away; at 56 degrees 3.577 m: beyond 3.5.
    ranges = cast_rays(0.0, 0.0, np.radians([55.0, 56.0]), NEAR, FAR, segments, circles)
    assert ranges[0] == pytest.approx(2.0 / math.cos(math.radians(55)))
    assert ranges[1] == math.inf
    assert cast_rays(0.0, 0.0, np.zeros(1), NEAR, 2.0, segments, circles)[0] == pytest.approx(2.0)


def test_circle_head_on_off_centre_and_grazing():
    segments, circles = outlines({'type': 'circle', 'center': [1.0, 0.0], 'radius': 0.15})
    # Off-centre: the beam at angle a passes the centre at distance sin(a); it enters the disc
    # at cos(a) - sqrt(r^2 - sin(a)^2).
    a = math.asin(0.1)
    grazing = math.asin(0.15)  # tangent: touches at distance cos(grazing)
    ranges = cast_rays(0.0, 0.0, np.array([0.0, a, grazing - 1e-9, grazing + 1e-9]), NEAR, FAR,
                       segments, circles)
    assert ranges[0] == pytest.approx(0.85)
    assert ranges[1] == pytest.approx(math.cos(a) - math.sqrt(0.15 ** 2 - 0.1 ** 2))
    assert ranges[2] == pytest.approx(math.cos(grazing), abs=1e-4)
    assert ranges[3] == math.inf


def test_hexagon_corner_and_face():
    # Regular hexagon at (2, 0), circumradius 1, corner on the x axis: the corner (1, 0) faces the
    # origin; a beam at 90 degrees from (2, -2) meets the bottom face y = -apothem.
    segments, circles = outlines({'type': 'regular_polygon', 'center': [2.0, 0.0], 'sides': 6,
                                  'circumradius': 1.0})
    assert cast_rays(0.0, 0.0, np.zeros(1), NEAR, FAR, segments, circles)[0] == pytest.approx(1.0)
    up = cast_rays(2.0, -2.0, np.array([math.pi / 2]), NEAR, FAR, segments, circles)[0]
    assert up == pytest.approx(2.0 - math.cos(math.pi / 6))


def test_ray_along_a_face_is_edge_on():
    # Square from (1, -1) to (3, 1). A beam along its bottom face y = -1 does not see that face
    # edge-on, but touches the end of the left face at the corner (1, -1).
    segments, circles = outlines({'type': 'polygon', 'points': [[1, -1], [3, -1], [3, 1], [1, 1]]})
    assert cast_rays(0.0, -1.0, np.zeros(1), NEAR, FAR, segments, circles)[0] == pytest.approx(1.0)
    # Along the bottom face from inside the corner region: starting at (2, -1) nothing is entered.
    assert cast_rays(2.0, -1.0, np.zeros(1), NEAR, FAR, segments, circles)[0] == math.inf


def test_ray_through_a_segment_end_hits():
    segments = np.array([[1.0, 0.0, 1.0, 1.0]])  # runs up; solid on its left (x < 1)
    # Seen from x > 1, looking back at -x: the beam through the end point (1, 0) still hits it.
    assert cast_rays(2.0, 0.0, np.array([math.pi]), NEAR, FAR, segments)[0] == pytest.approx(1.0)


def test_objects_inside_range_min_are_not_seen():
    # A thin wall 0.08 m ahead (inside the 0.12 m disc) and the 2 m wall behind it: only the
    # far one is seen. A pillar whose surface is 0.05 m away is not seen at all, not even its
    # far side: the beam starts inside it.
    thin = outlines({'type': 'box', 'center': [0.085, 0.0], 'size': [0.01, 0.5]},
                    {'type': 'box', 'center': [2.05, 0.0], 'size': [0.1, 4.0]})
    assert cast_rays(0.0, 0.0, np.zeros(1), NEAR, FAR, *thin)[0] == pytest.approx(2.0)
    pillar = outlines({'type': 'circle', 'center': [0.2, 0.0], 'radius': 0.15})
    assert cast_rays(0.0, 0.0, np.zeros(1), NEAR, FAR, *pillar)[0] == math.inf
    # Exactly at range_min a surface is seen.
    at_min = outlines({'type': 'box', 'center': [0.17, 0.0], 'size': [0.1, 0.5]})
    assert cast_rays(0.0, 0.0, np.zeros(1), NEAR, FAR, *at_min)[0] == pytest.approx(0.12)


def test_inside_a_ring_the_inner_wall_is_seen():
    segments, circles = outlines({'type': 'ring', 'center': [0, 0], 'sides': 4,
                                  'circumradius': math.sqrt(2), 'rotation': math.pi / 4,
                                  'thickness': 0.2})
    # A square room with inner walls at x, y = +-1.
    ranges = cast_rays(0.5, 0.0, np.array([0.0, math.pi]), NEAR, FAR, segments, circles)
    assert ranges == pytest.approx([0.5, 1.5])


def test_box_overlap_with_segments_and_circles():
    box = (-0.032, 0.07, 0.07)  # burger body around base_link
    wall = np.array([[0.05, -1.0, 0.05, 1.0]])
    # The body's front is at x = 0.038: a wall at x = 0.05 is clear, moved 0.013 m on it is not.
    assert not boxes_overlap((0.0, 0.0, 0.0), box, wall)[0]
    assert boxes_overlap((0.013, 0.0, 0.0), box, wall)[0]
    # A segment wholly inside the body overlaps; one parallel just outside does not.
    assert boxes_overlap((0.0, 0.0, 0.0), box, np.array([[-0.05, 0.0, -0.01, 0.0]]))[0]
    assert not boxes_overlap((0.0, 0.0, 0.0), box, np.array([[-1.0, 0.0701, 1.0, 0.0701]]))[0]
    # A circle touching the corner region: corner at (0.038, 0.07).
    near_corner = np.array([[0.038 + 0.1, 0.07 + 0.1, 0.1 * math.sqrt(2) + 1e-6]])
    assert boxes_overlap((0.0, 0.0, 0.0), box, circles=near_corner)[0]
    near_corner[0, 2] -= 2e-6
    assert not boxes_overlap((0.0, 0.0, 0.0), box, circles=near_corner)[0]
    # Turned 90 degrees, the front faces +y (at y = 0.038) and the sides are x = +-0.07.
    turned = (0.0, 0.0, math.pi / 2)
    assert boxes_overlap(turned, box, np.array([[-1, 0.03, 1, 0.03]]))[0]
    assert not boxes_overlap(turned, box, np.array([[-1, 0.045, 1, 0.045]]))[0]
    assert boxes_overlap(turned, box, np.array([[0.06, -1, 0.06, 1]]))[0]
    assert not boxes_overlap(turned, box, np.array([[0.08, -1, 0.08, 1]]))[0]


def test_box_outline_runs_counterclockwise_around_the_body():
    corners = box_outline(1.0, 2.0, 0.0, (-0.032, 0.07, 0.07))
    x, y, x1, y1 = corners.T
    assert np.sum(x * y1 - x1 * y) > 0
    assert sorted(set(np.round(x, 3))) == [0.898, 1.038]
    assert sorted(set(np.round(y, 3))) == [1.93, 2.07]


def test_many_lasers_at_once_see_what_each_sees_alone_but_not_their_own_body():
    # 25 bodies 0.6 m apart in turtlebot3_world's middle, each with a laser, at random headings:
    # cast together, every beam of every laser gives what casting it alone gives against the
    # world and the 24 other bodies (the laser's own body masked), to the last bit.
    world = load_world('turtlebot3_world')
    random = np.random.default_rng(7)
    grid = np.arange(5) * 0.6 - 1.2
    poses = np.array([(x, y, random.uniform(-math.pi, math.pi)) for x in grid for y in grid])
    bodies = box_outlines(poses, [(-0.032, 0.07, 0.07)] * len(poses))
    segments = np.concatenate([world.segments] + list(bodies))
    owners = np.concatenate([np.full(len(world.segments), -1),
                             np.repeat(np.arange(len(poses)), 4)])
    angles = np.linspace(0.0, 6.28319, 360)
    together = cast_scans(poses, angles, NEAR, FAR, segments, world.circles, owners)
    for index, (x, y, yaw) in enumerate(poses):
        others = np.concatenate([world.segments] + [body for other, body in enumerate(bodies)
                                                    if other != index])
        alone = cast_rays(x, y, angles + yaw, NEAR, FAR, others, world.circles)
        assert np.array_equal(together[index], alone)
        assert np.isfinite(alone).sum() > 100  # it sees its neighbours and the world
    # Its own body is 0.07 m around the laser, inside range_min, so a laser sees nothing of it
    # anyway; from farther off the mask is what hides it.
    body = box_outlines([(-1.0, 0.0, 0.0)], [(0.0, 0.1, 0.1)])[0]
    assert cast_scans([(-2.0, 0.0, 0.0)], [0.0], NEAR, FAR, body)[0, 0] == pytest.approx(0.9)
    assert cast_scans([(-2.0, 0.0, 0.0)], [0.0], NEAR, FAR, body, owners=[0] * 4)[0, 0] == math.inf
