"""fake_tb3 seen from above, as the page draws it (pure: no ROS).

The world's obstacles come from fake_tb3's own world files (fake_tb3.world), the robot's body and
laser position from its model (fake_tb3.models); the pose from odom, the scan from scan. Metres
and radians, world frame (fake_tb3's odom frame is the world frame: odometry starts at the spawn
pose).
"""
import math

from fake_tb3.models import get_model

TRAIL_STEP = 0.01  # m: a new trail point when the robot moved this far
MAX_TRAIL_POINTS = 20000  # then the older half is dropped


def world_shapes(world):
    """The obstacles as the page's JSON: [["polygon"|"hole", [[x, y], ...]] | ["circle", [cx, cy, r]]]."""
    shapes = []
    for kind, data in world.shapes:
        if kind == 'circle':
            shapes.append(['circle', [round(float(v), 4) for v in data]])
        else:
            shapes.append([kind, [[round(float(x), 4), round(float(y), 4)] for x, y in data]])
    return shapes


def scan_points(x, y, yaw, scan_offset, ranges, angle_min, angle_increment, range_min, range_max):
    """The scan's hits in the world frame, rounded to the millimetre, and the closest range (None:
    nothing in range). Beam i points at angle_min + i * angle_increment from base_scan, which sits
    at scan_offset (x forward, y left) on the robot."""
    c, s = math.cos(yaw), math.sin(yaw)
    laser_x = x + scan_offset[0] * c - scan_offset[1] * s
    laser_y = y + scan_offset[0] * s + scan_offset[1] * c
    points, closest = [], None
    for index, distance in enumerate(ranges):
        if not (math.isfinite(distance) and range_min <= distance <= range_max):
            continue
        angle = yaw + angle_min + index * angle_increment
        points.append([round(laser_x + distance * math.cos(angle), 3),
                       round(laser_y + distance * math.sin(angle), 3)])
        closest = distance if closest is None else min(closest, distance)
    return points, closest


def odometry_fields(message):
    """(x, y, yaw, linear, angular) of a nav_msgs/Odometry of a robot on the ground (the live view's
    and a replayed bag's: any object of that shape)."""
    pose, twist = message.pose.pose, message.twist.twist
    yaw = 2.0 * math.atan2(pose.orientation.z, pose.orientation.w)
    return (pose.position.x, pose.position.y, math.atan2(math.sin(yaw), math.cos(yaw)),
            twist.linear.x, twist.angular.z)


class Tb3Scene:
    """One fake_tb3 robot and its world. `generation` changes when the world or the robot is
    replaced (fake_tb3 started, restarted or gone), `version` with every change."""

    def __init__(self):
        self.present = False
        self.generation = 0
        self.version = 0
        self.world = None  # the page's JSON of the world: {name, shapes, bounds}
        self.body = None  # {length, width, offset_x, scan_offset}
        self.scan_offset = (0.0, 0.0)
        self.pose = None  # (x, y, yaw)
        self.speed = (0.0, 0.0)  # linear m/s, angular rad/s
        self.scan_seq = 0
        self.scan = []
        self.closest = None
        self.trail = []
        self.trail_dropped = 0  # trail points dropped from the front: page indices shift by this

    def start(self, world, model_name):
        """fake_tb3 (re)started in `world` (a fake_tb3.world.World) with a robot of this model."""
        model = get_model(model_name)
        bounds = world.bounds()
        self.world = {'name': world.name, 'shapes': world_shapes(world),
                      'bounds': [round(v, 4) for v in bounds] if bounds else None}
        self.body = {'length': model.body_length, 'width': model.body_width,
                     'offset_x': model.body_offset_x, 'model': model.name}
        self.scan_offset = model.scan_offset[:2]
        self.present = True
        self.pose, self.speed, self.scan, self.closest = None, (0.0, 0.0), [], None
        self.trail, self.trail_dropped = [], 0
        self.generation += 1
        self.version += 1

    def vanish(self):
        if self.present:
            self.present = False
            self.pose, self.scan, self.trail, self.closest = None, [], [], None
            self.generation += 1
            self.version += 1

    def on_odom(self, x, y, yaw, linear, angular):
        if not self.present or not all(map(math.isfinite, (x, y, yaw, linear, angular))):
            return
        self.pose, self.speed = (x, y, yaw), (linear, angular)
        if not self.trail or math.hypot(x - self.trail[-1][0], y - self.trail[-1][1]) >= TRAIL_STEP:
            self.trail.append([round(x, 3), round(y, 3)])
            if len(self.trail) > MAX_TRAIL_POINTS:
                half = len(self.trail) // 2
                self.trail = self.trail[half:]
                self.trail_dropped += half
        self.version += 1

    def on_scan(self, ranges, angle_min, angle_increment, range_min, range_max):
        if not self.present or self.pose is None:
            return
        self.scan, self.closest = scan_points(*self.pose, self.scan_offset, ranges, angle_min,
                                              angle_increment, range_min, range_max)
        self.scan_seq += 1
        self.version += 1

    @property
    def trail_end(self):
        """Index (counted from the first point ever) after the last trail point."""
        return self.trail_dropped + len(self.trail)

    def trail_since(self, index):
        """Trail points from index on, or None if some of them were dropped."""
        if index < self.trail_dropped:
            return None
        return self.trail[index - self.trail_dropped:]
