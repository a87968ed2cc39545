"""The IMU of a simulated TurtleBot3: what it reads from the robot's motion."""
from collections import namedtuple

GRAVITY = 9.80665

# yaw (rad), yaw rate (rad/s) and the acceleration (m/s^2) in the body frame: forward, left, up.
ImuReading = namedtuple('ImuReading', 'yaw angular_velocity acceleration_x acceleration_y '
                                      'acceleration_z')


class ImuSensor:
    """Readings taken every `period` seconds. The forward acceleration is the change of the
    forward speed since the previous reading over the period, the sideways one the centripetal
    acceleration (speed x yaw rate), the upward one gravity (the floor holds the robot up)."""

    def __init__(self, period):
        if not period > 0:
            raise ValueError('IMU period must be positive, got %r' % (period,))
        self.period = period
        self.previous_linear = 0.0

    def read(self, robot):
        linear, angular = robot.velocity
        reading = ImuReading(robot.yaw, angular, (linear - self.previous_linear) / self.period,
                             linear * angular, GRAVITY)
        self.previous_linear = linear
        return reading
