"""The LDS-01 scan: beams in turtlebot3_world computed by hand, noise, the scan's shape."""
import math

import numpy as np
import pytest

from fake_tb3.lidar import LDS_01, Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import load_world

INCREMENT = 6.28319 / 359


def spawn_scan(noise=0.0, seed=None):
    robot = SimRobot('', get_model('burger'), -2.0, -0.5, 0.0, Laser(noise_stddev=noise, seed=seed))
    return Simulation(load_world('turtlebot3_world'), [robot]).scan(robot)


def test_spec_matches_the_lds01():
    assert LDS_01.samples == 360
    assert LDS_01.angle_increment == pytest.approx(INCREMENT)
    assert LDS_01.beam_angles[-1] == pytest.approx(6.28319)
    assert (LDS_01.range_min, LDS_01.range_max) == (0.12, 3.5)


def test_scan_at_the_turtlebot3_world_spawn_by_hand():
    """The burger at (-2, -0.5, yaw 0) has its laser 0.032 m behind: at o = (-2.032, -0.5).

    The inner wall is a hexagon of apothem a = 2.9329 cos 30 = 2.53997; a face with outward normal n
    is the line n.p = a, met by a beam d from o after t = (a - n.o) / (n.d).
    """
    ranges = spawn_scan()
    assert len(ranges) == 360
    # Beam 0 (+x) runs along y = -0.5 between the pillar rows (|y| <= 0.15 and y <= -0.95) to the
    # big prism, whose face from (2.3268, 0) to (2.9134, -1.016) is at x = 2.6155 there:
    # 4.65 m away, beyond 3.5 -> inf.
    assert ranges[0] == math.inf
    # Beam 180 at 180*inc = 3.15039 rad, d = (-0.99996, -0.00880), meets the face with normal at
    # 210 deg, n = (-0.86603, -0.5): n.o = 2.00977, n.d = 0.87039, t = 0.53020 / 0.87039 = 0.60917.
    assert ranges[180] == pytest.approx(0.60917, abs=1e-4)
    # Beam 90 at 1.57518 rad, d = (-0.00439, 0.99999), face normal at 150 deg, n = (-0.86603, 0.5):
    # n.o = 1.50977, n.d = 0.50380, t = 1.03020 / 0.50380 = 2.04492 (the prism at (-1.8, 2.7)
    # starts at y = 2.0015, above the hit at y = 1.545).
    assert ranges[90] == pytest.approx(2.04492, abs=1e-4)
    # Beam 270 at 4.72555 rad, d = (0.01317, -0.99991), face normal at 210 deg:
    # n.d = 0.48855, t = 0.53020 / 0.48855 = 1.08525.
    assert ranges[270] == pytest.approx(1.08525, abs=2e-4)
    # Beam 28 at 0.490054 rad, d = (0.882308, 0.470673), towards the pillar at c = (-1.1, 0),
    # r = 0.15: m = o - c = (-0.932, -0.5), b = m.d = -1.057647, |m|^2 - r^2 = 1.096124,
    # b^2 = 1.118618, t = -b - sqrt(b^2 - 1.096124) = 1.057647 - 0.149979 = 0.907668.
    assert ranges[28] == pytest.approx(0.907668, abs=1e-5)


def test_noise_is_gaussian_seeded_and_clamped():
    exact = spawn_scan()
    noisy = spawn_scan(noise=0.01, seed=3)
    assert np.array_equal(noisy, spawn_scan(noise=0.01, seed=3))
    assert not np.array_equal(noisy, spawn_scan(noise=0.01, seed=4))
    seen = np.isfinite(exact)
    assert np.array_equal(seen, np.isfinite(noisy))  # no hit stays +inf, hits stay finite
    errors = np.concatenate([spawn_scan(noise=0.01, seed=s)[seen] - exact[seen] for s in range(20)])
    assert abs(errors.mean()) < 0.002
    assert 0.009 < errors.std() < 0.011
    huge = spawn_scan(noise=10.0, seed=1)[seen]
    assert huge.min() == pytest.approx(0.12) and huge.max() == pytest.approx(3.5)


def test_bad_noise_is_refused():
    for bad in (-0.1, math.nan, math.inf):
        with pytest.raises(ValueError, match='noise stddev'):
            Laser(noise_stddev=bad)
