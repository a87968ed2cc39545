"""The LDS-01 laser of the TurtleBot3 as Gazebo simulates it."""
import functools
import math
from dataclasses import dataclass

import numpy as np

from fake_tb3.geometry import cast_scans


@dataclass(frozen=True)
class LaserSpec:
    """Geometry of the scan. Beam i points at angle_min + i * angle_increment in base_scan."""
    samples: int = 360
    angle_min: float = 0.0
    angle_max: float = 6.28319  # so the last beam overlaps the first, as in Gazebo
    range_min: float = 0.12
    range_max: float = 3.5

    @property
    def angle_increment(self):
        return (self.angle_max - self.angle_min) / (self.samples - 1)

    @functools.cached_property
    def beam_angles(self):
        """The beams' angles, made once (read-only: every scan shares them)."""
        angles = self.angle_min + self.angle_increment * np.arange(self.samples)
        angles.flags.writeable = False
        return angles


LDS_01 = LaserSpec()


class Laser:
    """One robot's laser. Its scans (scan_all) are the distance to the first surface in
    [range_min, range_max] along each beam, plus Gaussian noise on the values in range (then
    clamped to the range); +inf where nothing is hit.

    noise_stddev 0 gives exact distances; seed makes the noise repeatable (None: random).
    """

    def __init__(self, spec=LDS_01, noise_stddev=0.01, seed=None):
        if not (noise_stddev >= 0 and math.isfinite(noise_stddev)):
            raise ValueError('noise stddev must be a finite number >= 0, got %r' % (noise_stddev,))
        self.spec = spec
        self.noise_stddev = noise_stddev
        self._random = np.random.default_rng(seed)

    def add_noise(self, ranges):
        """Exact `ranges` of one scan made noisy in place; returns them."""
        if self.noise_stddev > 0:
            spec = self.spec
            hit = np.isfinite(ranges)
            noisy = ranges[hit] + self._random.normal(0.0, self.noise_stddev, int(hit.sum()))
            # np.clip's own checks cost more than its two comparisons.
            ranges[hit] = np.minimum(np.maximum(noisy, spec.range_min, out=noisy), spec.range_max,
                                     out=noisy)
        return ranges


def scan_all(lasers, poses, segments, circles, owners=None):
    """A scan of each of `lasers` (Laser) at its pose (x, y, yaw of the laser in the world), all
    cast at once: a list of ranges arrays (float, spec.samples each). owners: for each segment,
    the index of the laser that does not see it (its own robot's body), or -1."""
    scans = [None] * len(lasers)
    poses = np.asarray(poses, dtype=float).reshape(-1, 3)
    for spec in set(laser.spec for laser in lasers):
        chosen = [index for index, laser in enumerate(lasers) if laser.spec == spec]
        group_owners = None
        if owners is not None:  # owners as indices among this spec's lasers
            among = np.full(len(lasers) + 1, -1)
            among[chosen] = np.arange(len(chosen))
            group_owners = among[np.asarray(owners)]
        ranges = cast_scans(poses[chosen], spec.beam_angles, spec.range_min, spec.range_max,
                            segments, circles, group_owners)
        for index, row in zip(chosen, ranges):
            scans[index] = lasers[index].add_noise(row)
    return scans
