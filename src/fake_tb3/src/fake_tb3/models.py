"""The TurtleBot3 models: the numbers of the Gazebo robots that the simulator needs."""
import functools
import math
from dataclasses import dataclass

# base_footprint -> base_link: the body sits 1 cm above the floor.
BASE_LINK_HEIGHT = 0.010


@dataclass(frozen=True)
class RobotModel:
    """One TurtleBot3 model. Offsets are in metres from base_link (x forward, y left, z up)."""
    name: str
    wheel_radius: float
    wheel_separation: float
    max_linear: float   # m/s, limit of the real robot
    max_angular: float  # rad/s
    body_length: float  # collision box along x
    body_width: float   # collision box along y
    body_offset_x: float  # x of the collision box centre
    body_height: float  # collision box height
    body_centre_z: float  # z of the collision box centre
    scan_offset: tuple  # base_scan (x, y, z)
    imu_offset: tuple   # imu_link (x, y, z)
    wheel_offset_y: float  # |y| of the wheel joints in the URDF (about half the separation)
    casters: tuple      # (x, y, z) of each caster
    camera_offset: tuple = None  # camera_link (x, y, z), waffles only

    @functools.cached_property
    def body_corner_radius(self):
        """Distance from base_footprint to the body's farthest corner: how far a spin sweeps."""
        return math.hypot(abs(self.body_offset_x) + self.body_length / 2, self.body_width / 2)

    def clamp(self, linear, angular):
        """(linear, angular) limited to what the real robot can do."""
        return (max(-self.max_linear, min(self.max_linear, linear)),
                max(-self.max_angular, min(self.max_angular, angular)))


_WAFFLE = dict(wheel_radius=0.033, wheel_separation=0.287, max_linear=0.26, max_angular=1.82,
               body_length=0.266, body_width=0.266, body_offset_x=-0.064, body_height=0.094,
               body_centre_z=0.047,
               scan_offset=(-0.064, 0.0, 0.122), imu_offset=(0.0, 0.0, 0.068),
               wheel_offset_y=0.144,
               casters=((-0.177, 0.064, -0.004), (-0.177, -0.064, -0.004)))

MODELS = {
    'burger': RobotModel(name='burger', wheel_radius=0.033, wheel_separation=0.160,
                         max_linear=0.22, max_angular=2.84,
                         body_length=0.140, body_width=0.140, body_offset_x=-0.032,
                         body_height=0.143, body_centre_z=0.070, scan_offset=(-0.032, 0.0, 0.172),
                         imu_offset=(-0.032, 0.0, 0.068), wheel_offset_y=0.08,
                         casters=((-0.081, 0.0, -0.004),)),
    'waffle': RobotModel(name='waffle', camera_offset=(0.064, -0.065, 0.094), **_WAFFLE),
    'waffle_pi': RobotModel(name='waffle_pi', camera_offset=(0.073, -0.011, 0.084), **_WAFFLE),
}


class UnknownModelError(ValueError):
    """A model name that is not a TurtleBot3 model."""


def get_model(name):
    """The RobotModel called `name` (burger, waffle, waffle_pi); UnknownModelError otherwise."""
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise UnknownModelError('unknown TurtleBot3 model %r: use one of %s'
                                % (name, ', '.join(sorted(MODELS)))) from None
