"""The turtlesim world without ROS: turtles, their kinematics, pens, teleports, spawning and killing.

Numbers and order of operations are those of ROS 1 turtlesim (0.10), so that poses match the
original to float precision. Positions are kept as the original keeps them, in the widget's frame
(x right, y DOWN from the top edge, metres); poses are reported with y up from the bottom edge.

The caller drives it: one `tick(now)` per TICK_SECONDS with the wall-clock time `now` in seconds, and
requests (velocity commands, teleports, spawn/kill/clear/reset) between ticks. Errors in requests
raise TurtlesimError, whose text is what the user should read; log lines go to `log`, an object
with info() and warning() (a logging.Logger will do).
"""
import bisect
import math
import random
import re
import struct

from turtlesim.canvas import Canvas

PX_PER_METER = 45
WORLD_SIZE = (500 - 1) / PX_PER_METER  # 11.088889 m, both width and height
PI = 3.14159265  # the original's constant, not math.pi: it decides where theta wraps
# The original's fixed step (16 ms, 62.5 ticks a second): each tick moves every turtle by its velocity
# times this and publishes its pose. Written here only: the rest of the course imports it.
TICK_SECONDS = 0.016
COMMAND_TIMEOUT = 1.0
DEFAULT_BACKGROUND = (69, 86, 255)
DEFAULT_PEN_COLOR = (179, 184, 255)
DEFAULT_PEN_WIDTH = 3
FLOAT32_MAX = 3.4028234663852886e38
ICON_STYLES = 6  # how many looks a turtle icon can have; each spawn picks one at random

# A ROS graph resource name, optionally private (~) or absolute (/): what a turtle name becomes
# as the namespace of its topics and services.
_NAME_PATTERN = re.compile(r'^[~/]?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$')


class TurtlesimError(Exception):
    """A request that cannot be carried out; the text says why."""


def wrap_angle(theta):
    """theta wrapped to [-PI, PI) the way the original does it (so PI itself becomes -PI)."""
    wrapped = theta - 2.0 * PI * math.floor((theta + PI) / (2.0 * PI))
    if -PI <= wrapped < PI:
        return wrapped
    # Only for |theta| so large that the subtraction above loses all precision.
    return math.fmod(math.fmod(theta, 2.0 * PI) + 3.0 * PI, 2.0 * PI) - PI


def check_name(name):
    """Raise TurtlesimError unless `name` can name a turtle's topics and services."""
    if not _NAME_PATTERN.match(name):
        raise TurtlesimError(
            'Invalid turtle name [%s]: a name starts with a letter (optionally after "/" or "~") '
            'and contains only letters, digits, "_" and "/" between words' % name)


def check_finite(what, **values):
    """Raise TurtlesimError naming the offending fields if any value is NaN or infinite."""
    bad = ['%s=%s' % (key, value) for key, value in values.items() if not math.isfinite(value)]
    if bad:
        raise TurtlesimError('%s: %s must be a finite number' % (what, ', '.join(bad)))


def as_float32(value):
    """The value rounded to float32, as the original's spawnTurtle(float x, float y, float angle) does."""
    return struct.unpack('f', struct.pack('f', value))[0]


def pixel_index(coordinate):
    """The pixel under a coordinate in metres (Qt's qRound for non-negative values)."""
    return int(math.floor(coordinate * PX_PER_METER + 0.5))


def _by_name(turtle):
    return turtle.name


class Turtle:
    """One turtle: pose (x right, qt_y down, metres), commanded velocities, pen, pending teleports."""

    def __init__(self, name, x, y, theta, icon):
        self.name = name
        self.x = x
        self.qt_y = WORLD_SIZE - y
        self.theta = theta
        self.vx = self.vy = self.wz = 0.0
        self.last_command = None  # wall time of the last cmd_vel; None: never commanded
        self.pen_on = True
        self.pen_color = DEFAULT_PEN_COLOR
        self.pen_width = DEFAULT_PEN_WIDTH
        self.teleports = []  # (relative, a, b, theta): absolute (x, y, theta) or relative (linear, angular)
        self.color = (0, 0, 0)  # colour sensor: the path pixel under the turtle at the last tick
        self.color_version = -1  # canvas version the colour was read from
        self.settled = False  # at rest, wrapped and clamped: a tick would change nothing but the colour
        self.icon = icon

    @property
    def y(self):
        return WORLD_SIZE - self.qt_y

    @property
    def linear_velocity(self):
        return math.hypot(self.vx, self.vy)


class World:
    """All turtles and the path canvas. Not thread-safe: call it from one thread at a time."""

    def __init__(self, log, background=DEFAULT_BACKGROUND, name_key=None, rng=None):
        self.log = log
        self.canvas = Canvas(background)
        self._name_key = name_key or (lambda name: name)
        self._turtles = {}  # name_key(name) -> Turtle
        self._ordered = []  # update order: by name, as the original's std::map
        self._active = []  # the turtles of _ordered that are not settled, in the same order
        # The canvas version that every settled turtle has sensed; None when some may not have.
        # While the canvas stays at it, a tick needs to visit only the active turtles.
        self._sensed_version = None
        self._spawn_counter = 0
        self._rng = rng or random.Random()
        self.revision = 0  # changes whenever a turtle appears, disappears, moves or turns
        self.roster = 0  # changes whenever a turtle appears or disappears
        self.spawn('', WORLD_SIZE / 2.0, WORLD_SIZE / 2.0, 0.0)

    # --- queries ---
    def turtles(self):
        """The turtles in update order (by name)."""
        return list(self._ordered)

    def turtle(self, name):
        """The turtle called `name`, or None."""
        return self._turtles.get(self._name_key(name))

    def _existing(self, name):
        turtle = self.turtle(name)
        if turtle is None:
            raise TurtlesimError('There is no turtle named [%s]' % name)
        return turtle

    # --- requests ---
    def spawn(self, name, x, y, theta):
        """Add a turtle; an empty name becomes turtleN. Returns the name used."""
        x, y, theta = (as_float32(value) if abs(value) <= FLOAT32_MAX else value for value in (x, y, theta))
        check_finite('Cannot spawn a turtle', x=x, y=y, theta=theta)
        if name:
            check_name(name)
            if self.turtle(name) is not None:
                raise TurtlesimError('A turtled named [%s] already exists' % name)
        else:
            while True:
                self._spawn_counter += 1
                name = 'turtle%d' % self._spawn_counter
                if self.turtle(name) is None:
                    break
        self._turtles[self._name_key(name)] = Turtle(name, x, y, theta, self._rng.randrange(ICON_STYLES))
        self._update_order()
        self.log.info('Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]' % (name, x, y, theta))
        return name

    def kill(self, name):
        key = self._name_key(name)
        if key not in self._turtles:
            raise TurtlesimError('Tried to kill turtle [%s], which does not exist' % name)
        del self._turtles[key]
        self._update_order()

    def _update_order(self):
        self._ordered = sorted(self._turtles.values(), key=_by_name)
        self._active = [turtle for turtle in self._ordered if not turtle.settled]
        self.revision += 1
        self.roster += 1

    def _wake(self, turtle):
        """A request changed what the turtle's next update does: it is visited at the next tick."""
        if turtle.settled:
            turtle.settled = False
            bisect.insort(self._active, turtle, key=_by_name)

    def clear(self, background):
        self.log.info('Clearing turtlesim.')
        self.canvas.fill(background)

    def reset(self, background):
        """Remove every turtle, restart the name counter, spawn turtle1 in the centre, clear."""
        self.log.info('Resetting turtlesim.')
        self._turtles.clear()
        self._spawn_counter = 0
        self.spawn('', WORLD_SIZE / 2.0, WORLD_SIZE / 2.0, 0.0)
        self.canvas.fill(background)

    def command_velocity(self, name, vx, vy, wz, now):
        """A cmd_vel: these velocities hold until the next command or for COMMAND_TIMEOUT seconds."""
        check_finite('Ignoring a velocity command for [%s]' % name, **{
            'linear.x': vx, 'linear.y': vy, 'angular.z': wz})
        turtle = self._existing(name)
        turtle.vx, turtle.vy, turtle.wz = vx, vy, wz
        turtle.last_command = now
        self._wake(turtle)

    def set_pen(self, name, r, g, b, width, off):
        """off != 0 only lifts the pen; otherwise pen down with this colour, width 0 meaning 1."""
        turtle = self._existing(name)
        if off:
            turtle.pen_on = False
        else:
            turtle.pen_on = True
            turtle.pen_color = (r, g, b)
            turtle.pen_width = width if width else 1

    def teleport_absolute(self, name, x, y, theta):
        """Queued: applied at the start of the turtle's next update."""
        check_finite('Cannot teleport [%s]' % name, x=x, y=y, theta=theta)
        turtle = self._existing(name)
        turtle.teleports.append((False, x, y, theta))
        self._wake(turtle)

    def teleport_relative(self, name, linear, angular):
        """Queued: turn by `angular`, then move `linear` along the new heading."""
        check_finite('Cannot teleport [%s]' % name, linear=linear, angular=angular)
        turtle = self._existing(name)
        turtle.teleports.append((True, linear, angular, None))
        self._wake(turtle)

    # --- the update loop ---
    def tick(self, now):
        """One step (TICK_SECONDS) of every turtle, in name order.

        A settled turtle only senses the colour under it, and only when the canvas changed since it
        last did; so while the canvas stays as every settled turtle last sensed it, only the active
        turtles are visited, until one of them draws: from there on, every turtle is visited."""
        canvas = self.canvas
        if self._sensed_version != canvas.version:
            self._visit_all(self._ordered, now)
            return
        version = canvas.version
        active = self._active
        for done, turtle in enumerate(active, 1):
            self._update(turtle, now)
            self.revision += 1
            if canvas.version != version:  # it drew: those after it sense the new canvas
                rest = self._ordered[bisect.bisect_right(self._ordered, turtle.name, key=_by_name):]
                still_active = [moved for moved in active[:done] if not moved.settled]
                self._visit_all(rest, now)
                self._active = still_active + self._active
                self._sensed_version = None  # those before it sensed the canvas before it drew
                return
        self._active = [turtle for turtle in active if not turtle.settled]

    def _visit_all(self, turtles, now):
        """Update the active turtles and let the settled ones sense a changed canvas, in order;
        self._active becomes the turtles of `turtles` still active."""
        canvas = self.canvas
        active = []
        first_sensed = None  # the canvas version the first turtle settled after its turn sensed
        for turtle in turtles:
            if turtle.settled:
                if turtle.color_version != canvas.version:
                    self._sense_color(turtle)
            else:
                self._update(turtle, now)
                self.revision += 1
                if not turtle.settled:
                    active.append(turtle)
                    continue
            if first_sensed is None:
                first_sensed = turtle.color_version
        self._active = active
        self._sensed_version = canvas.version if first_sensed in (None, canvas.version) else None

    def _draw(self, turtle, old_x, old_qt_y):
        self.canvas.draw_line(old_x * PX_PER_METER, old_qt_y * PX_PER_METER,
                              turtle.x * PX_PER_METER, turtle.qt_y * PX_PER_METER,
                              turtle.pen_color, turtle.pen_width)

    def _sense_color(self, turtle):
        turtle.color = self.canvas.pixel(pixel_index(turtle.x), pixel_index(turtle.qt_y))
        turtle.color_version = self.canvas.version

    def _update(self, turtle, now):
        for relative, first, second, theta in turtle.teleports:
            old_x, old_qt_y = turtle.x, turtle.qt_y
            if relative:
                turtle.theta += second
                turtle.x += math.cos(turtle.theta) * first
                turtle.qt_y -= math.sin(turtle.theta) * first
            else:
                turtle.x = first
                turtle.qt_y = max(0.0, WORLD_SIZE - second)
                turtle.theta = theta
            if turtle.pen_on:
                self._draw(turtle, old_x, old_qt_y)
        turtle.teleports = []

        if turtle.last_command is None or now - turtle.last_command > COMMAND_TIMEOUT:
            turtle.vx = turtle.vy = turtle.wz = 0.0

        old_x, old_qt_y = turtle.x, turtle.qt_y
        turtle.theta = wrap_angle(turtle.theta + turtle.wz * TICK_SECONDS)
        cos, sin = math.cos(turtle.theta), math.sin(turtle.theta)
        # Each product is scaled by dt before adding, so huge finite velocities cannot overflow.
        turtle.x += cos * turtle.vx * TICK_SECONDS - sin * turtle.vy * TICK_SECONDS
        turtle.qt_y -= sin * turtle.vx * TICK_SECONDS + cos * turtle.vy * TICK_SECONDS

        if not (0.0 <= turtle.x <= WORLD_SIZE and 0.0 <= turtle.qt_y <= WORLD_SIZE):
            self.log.warning('Oh no! I hit the wall! (Clamping from [x=%f, y=%f])' % (turtle.x, turtle.qt_y))
            turtle.x = min(max(turtle.x, 0.0), WORLD_SIZE)
            turtle.qt_y = min(max(turtle.qt_y, 0.0), WORLD_SIZE)

        self._sense_color(turtle)
        if turtle.pen_on and (turtle.x, turtle.qt_y) != (old_x, old_qt_y):
            self._draw(turtle, old_x, old_qt_y)
        turtle.settled = turtle.vx == 0.0 and turtle.vy == 0.0 and turtle.wz == 0.0
