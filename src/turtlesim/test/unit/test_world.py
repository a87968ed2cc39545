"""The turtlesim core against hand-computed values (no ROS master needed)."""
import math

import pytest

from turtlesim.world import (DEFAULT_BACKGROUND, DEFAULT_PEN_COLOR, PI, TICK_SECONDS, WORLD_SIZE,
                             TurtlesimError, World, wrap_angle)

CENTRE = 5.544444561004639  # WORLD_SIZE / 2 rounded to float32, where turtle1 starts
TOLERANCE = 1e-6


class RecordingLog:
    def __init__(self):
        self.lines = []

    def info(self, text):
        self.lines.append(('INFO', text))

    def warning(self, text):
        self.lines.append(('WARN', text))

    def texts(self, level):
        return [text for line_level, text in self.lines if line_level == level]


class Clock:
    """Tick times of a simulator running exactly on time."""

    def __init__(self):
        self.now = 1000.0

    def run(self, world, ticks):
        for _ in range(ticks):
            world.tick(self.now)
            self.now += TICK_SECONDS


@pytest.fixture
def log():
    return RecordingLog()


@pytest.fixture
def world(log):
    return World(log)


@pytest.fixture
def clock():
    return Clock()


def pose(world, name='turtle1'):
    turtle = world.turtle(name)
    return turtle.x, turtle.y, turtle.theta


def assert_pose(world, x, y, theta, name='turtle1'):
    assert pose(world, name) == pytest.approx((x, y, theta), abs=TOLERANCE)


# --- start-up ---
def test_turtle1_starts_in_the_centre_facing_east(world, log):
    assert WORLD_SIZE == pytest.approx(11.088889, abs=TOLERANCE)
    assert [turtle.name for turtle in world.turtles()] == ['turtle1']
    assert_pose(world, CENTRE, CENTRE, 0.0)
    assert log.texts('INFO') == ['Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]']


# --- kinematics ---
def test_one_command_moves_63_ticks_then_the_turtle_stops(world, clock):
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 200)
    # ticks at 0, 16, ..., 992 ms after the command move; at 1008 ms the command has expired
    assert_pose(world, CENTRE + 63 * TICK_SECONDS, CENTRE, 0.0)
    assert world.turtle('turtle1').linear_velocity == 0.0


def test_a_fresh_command_keeps_the_turtle_moving(world, clock):
    for _ in range(3):
        world.command_velocity('turtle1', 0.5, 0.0, 0.0, clock.now)
        clock.run(world, 50)
    clock.run(world, 100)
    assert_pose(world, CENTRE + (100 + 63) * 0.5 * TICK_SECONDS, CENTRE, 0.0)


def test_arc_matches_the_closed_form_sum(world, clock):
    """vx = 1, wz = 1: theta_k = k*a with a = TICK_SECONDS; x, y sum cos/sin of the NEW theta of each tick
    (worked out by hand below with the original's 16 ms: this pins TICK_SECONDS to it)."""
    ticks, step = 50, TICK_SECONDS
    world.command_velocity('turtle1', 1.0, 0.0, 1.0, clock.now)
    clock.run(world, ticks)
    # sum_{k=1..n} cos(k a) = sin(n a / 2) cos((n + 1) a / 2) / sin(a / 2), the same with sin for y
    scale = math.sin(ticks * step / 2) / math.sin(step / 2)
    expected_x = CENTRE + step * scale * math.cos((ticks + 1) * step / 2)
    expected_y = CENTRE + step * scale * math.sin((ticks + 1) * step / 2)
    assert_pose(world, expected_x, expected_y, ticks * step)
    assert expected_x == pytest.approx(CENTRE + 0.7149144, abs=1e-6)  # the same numbers, worked out by hand
    assert expected_y == pytest.approx(CENTRE + 0.3090257, abs=1e-6)


def test_sideways_velocity_uses_the_heading(world, clock):
    world.teleport_absolute('turtle1', 3.0, 4.0, PI / 2)
    world.command_velocity('turtle1', 0.0, 2.0, 0.0, clock.now)
    clock.run(world, 10)
    # heading north, +vy (to the left) moves west: x -= 2 m/s * TICK_SECONDS per tick
    assert_pose(world, 3.0 - 10 * 2.0 * TICK_SECONDS, 4.0, PI / 2)


def test_backwards_reports_positive_linear_velocity(world, clock):
    world.command_velocity('turtle1', -1.5, 0.0, -0.25, clock.now)
    clock.run(world, 1)
    turtle = world.turtle('turtle1')
    assert (turtle.linear_velocity, turtle.wz) == (1.5, -0.25)


# --- angle wrap ---
@pytest.mark.parametrize('theta, wrapped', [
    (PI, -PI), (-PI, -PI), (10.0, -2.566370), (-10.0, 2.566370), (3.0, 3.0), (7.0, 0.7168147),
])
def test_wrap_angle(theta, wrapped):
    assert wrap_angle(theta) == pytest.approx(wrapped, abs=TOLERANCE)


def test_theta_pi_becomes_minus_pi_exactly(world, clock):
    world.teleport_absolute('turtle1', 5.0, 5.0, PI)
    clock.run(world, 1)
    assert world.turtle('turtle1').theta == -PI


def test_turning_past_pi_wraps(world, clock):
    world.teleport_absolute('turtle1', 5.0, 5.0, 3.14)
    world.command_velocity('turtle1', 0.0, 0.0, 1.0, clock.now)
    clock.run(world, 1)
    assert world.turtle('turtle1').theta == pytest.approx(3.156 - 2 * PI, abs=TOLERANCE)


def test_huge_angles_still_wrap_into_range(world, clock):
    world.teleport_absolute('turtle1', 5.0, 5.0, 1e30)
    world.command_velocity('turtle1', 0.0, 0.0, 1e300, clock.now)
    clock.run(world, 3)
    assert -PI <= world.turtle('turtle1').theta < PI


# --- walls ---
def test_teleport_beyond_the_right_wall_clamps_with_a_warning(world, log, clock):
    world.teleport_absolute('turtle1', 12.0, 3.0, 0.0)
    clock.run(world, 1)
    assert_pose(world, WORLD_SIZE, 3.0, 0.0)
    assert log.texts('WARN') == ['Oh no! I hit the wall! (Clamping from [x=12.000000, y=8.088889])']


def test_teleport_above_the_top_is_clamped_silently(world, log, clock):
    world.teleport_absolute('turtle1', 3.0, 12.0, 0.0)
    clock.run(world, 1)
    assert_pose(world, 3.0, WORLD_SIZE, 0.0)
    assert log.texts('WARN') == []


def test_spawn_above_the_top_warns_in_widget_coordinates(world, log, clock):
    world.spawn('high', 5.0, 12.0, 0.0)
    clock.run(world, 1)
    assert_pose(world, 5.0, WORLD_SIZE, 0.0, name='high')
    assert log.texts('WARN') == ['Oh no! I hit the wall! (Clamping from [x=5.000000, y=-0.911111])']


def test_spawn_out_of_range_is_clamped_on_the_next_tick(world, log, clock):
    world.spawn('far', 20.0, -5.0, 0.0)
    assert_pose(world, 20.0, -5.0, 0.0, name='far')
    clock.run(world, 1)
    assert_pose(world, WORLD_SIZE, 0.0, 0.0, name='far')
    assert log.texts('WARN') == ['Oh no! I hit the wall! (Clamping from [x=20.000000, y=16.088889])']


def test_pushing_into_a_wall_warns_every_tick_and_keeps_the_velocity(world, log, clock):
    world.teleport_absolute('turtle1', WORLD_SIZE - 0.02, 2.0, 0.0)
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 5)
    assert_pose(world, WORLD_SIZE, 2.0, 0.0)
    assert len(log.texts('WARN')) == 4  # the first tick reaches WORLD_SIZE - 0.004, still inside
    assert world.turtle('turtle1').linear_velocity == 1.0


def test_huge_finite_velocities_stay_finite_at_the_wall(world, clock):
    world.command_velocity('turtle1', 1e308, -1e308, 0.0, clock.now)
    clock.run(world, 2)
    x, y, theta = pose(world)
    assert (x, y) == (WORLD_SIZE, 0.0)
    assert math.isfinite(theta)


# --- teleports ---
def test_teleports_apply_at_the_next_tick_in_order(world, clock):
    world.teleport_absolute('turtle1', 1.0, 2.0, 0.5)
    world.teleport_relative('turtle1', 2.0, PI / 2 - 0.5)
    assert_pose(world, CENTRE, CENTRE, 0.0)
    clock.run(world, 1)
    assert_pose(world, 1.0, 4.0, PI / 2)


def test_teleport_keeps_the_velocities(world, clock):
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    world.teleport_absolute('turtle1', 1.0, 1.0, 0.0)
    clock.run(world, 1)
    assert_pose(world, 1.016, 1.0, 0.0)


def test_teleport_draws_a_line_when_the_pen_is_down(world, clock):
    world.set_pen('turtle1', 0, 255, 0, 3, 0)
    world.teleport_absolute('turtle1', 1.0, CENTRE, 0.0)
    clock.run(world, 1)
    row = world.canvas.pixels[round((WORLD_SIZE - CENTRE) * 45)]
    green = [col for col in range(500) if tuple(row[col]) == (0, 255, 0)]
    # from x = 1 m (45 px) to the centre (249.500005 px), with square caps of 1.5 px at both ends
    assert (green[0], green[-1]) == (44, 251)


def test_teleport_relative_without_pen_draws_nothing(world, clock):
    world.set_pen('turtle1', 0, 0, 0, 0, 1)
    world.teleport_relative('turtle1', 3.0, 1.0)
    clock.run(world, 1)
    assert (world.canvas.pixels == DEFAULT_BACKGROUND).all()
    assert_pose(world, CENTRE + 3 * math.cos(1.0), CENTRE + 3 * math.sin(1.0), 1.0)


# --- pen and colour sensor ---
def pen_rows(world, colour, col):
    return [row for row in range(500) if tuple(world.canvas.pixels[row, col]) == colour]


def test_default_pen_draws_three_pixels_wide(world, clock):
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 30)
    assert pen_rows(world, DEFAULT_PEN_COLOR, 260) == [248, 249, 250]


@pytest.mark.parametrize('width, rows', [(0, [249]), (1, [249]), (2, [249, 250]), (7, list(range(246, 253)))])
def test_pen_width(world, clock, width, rows):
    world.set_pen('turtle1', 255, 0, 0, width, 0)
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 30)
    assert pen_rows(world, (255, 0, 0), 260) == rows


def test_pen_off_only_lifts_the_pen(world, clock):
    world.set_pen('turtle1', 255, 0, 0, 5, 0)
    world.set_pen('turtle1', 1, 2, 3, 9, 1)
    turtle = world.turtle('turtle1')
    assert (turtle.pen_on, turtle.pen_color, turtle.pen_width) == (False, (255, 0, 0), 5)
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 30)
    assert (world.canvas.pixels == DEFAULT_BACKGROUND).all()


def test_colour_sensor_reads_before_the_line_of_the_tick(world, clock):
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 1)
    assert world.turtle('turtle1').color == DEFAULT_BACKGROUND
    clock.run(world, 1)
    assert world.turtle('turtle1').color == DEFAULT_PEN_COLOR


def test_colour_sensor_follows_the_canvas_under_a_resting_turtle(world, clock):
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 100)
    assert world.turtle('turtle1').color == DEFAULT_PEN_COLOR
    world.clear((10, 20, 30))
    clock.run(world, 1)
    assert world.turtle('turtle1').color == (10, 20, 30)
    world.spawn('painter', CENTRE + 1.008, 1.0, 0.0)
    world.set_pen('painter', 0, 0, 255, 5, 0)
    world.teleport_absolute('painter', CENTRE + 1.008, 10.0, 0.0)  # a line across turtle1
    clock.run(world, 1)
    assert world.turtle('turtle1').color == (0, 0, 255)


# --- spawn, kill, clear, reset ---
def test_spawn_names_come_from_a_counter_that_only_rises(world):
    assert world.spawn('', 1, 1, 0) == 'turtle2'
    world.kill('turtle2')
    assert world.spawn('', 1, 1, 0) == 'turtle3'
    world.spawn('turtle4', 1, 1, 0)
    assert world.spawn('', 1, 1, 0) == 'turtle5'
    world.kill('turtle1')
    assert world.spawn('', 1, 1, 0) == 'turtle6'


def test_reset_restarts_the_counter_and_keeps_only_turtle1(world, log, clock):
    world.spawn('', 1, 1, 0)
    world.spawn('other', 1, 1, 0)
    world.set_pen('turtle1', 0, 0, 0, 9, 0)
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 10)
    log.lines.clear()
    world.reset((1, 2, 3))
    assert [turtle.name for turtle in world.turtles()] == ['turtle1']
    turtle = world.turtle('turtle1')
    assert (turtle.pen_color, turtle.pen_width, turtle.linear_velocity) == (DEFAULT_PEN_COLOR, 3, 0.0)
    assert_pose(world, CENTRE, CENTRE, 0.0)
    assert (world.canvas.pixels == (1, 2, 3)).all()
    assert world.spawn('', 1, 1, 0) == 'turtle2'
    assert log.texts('INFO')[:2] == [
        'Resetting turtlesim.', 'Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]']


def test_clear_repaints_but_keeps_turtles_and_pens(world, log, clock):
    world.set_pen('turtle1', 9, 9, 9, 4, 0)
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    clock.run(world, 10)
    world.clear((7, 8, 9))
    assert (world.canvas.pixels == (7, 8, 9)).all()
    assert_pose(world, CENTRE + 0.16, CENTRE, 0.0)
    assert world.turtle('turtle1').pen_color == (9, 9, 9)
    assert log.texts('INFO')[-1] == 'Clearing turtlesim.'


def test_spawn_logs_and_the_last_turtle_may_be_killed(world, log):
    world.spawn('leo', 1.5, 2.25, -1.0)
    assert log.texts('INFO')[-1] == 'Spawning turtle [leo] at x=[1.500000], y=[2.250000], theta=[-1.000000]'
    world.kill('turtle1')
    world.kill('leo')
    assert world.turtles() == []


def test_duplicate_name_fails(world):
    with pytest.raises(TurtlesimError, match=r'^A turtled named \[turtle1\] already exists$'):
        world.spawn('turtle1', 1, 1, 0)


@pytest.mark.parametrize('name', ['1abc', 'foo bar', 'with-dash', 'a//b', 'tail/', '~', 'ü'])
def test_invalid_names_fail(world, name):
    with pytest.raises(TurtlesimError, match=r'Invalid turtle name \[%s\]' % name):
        world.spawn(name, 1, 1, 0)
    assert [turtle.name for turtle in world.turtles()] == ['turtle1']


@pytest.mark.parametrize('name', ['a/b', '/abs', '~priv', 'Turtle_2'])
def test_names_with_namespaces_are_accepted(world, name):
    assert world.spawn(name, 1, 1, 0) == name


def test_names_that_resolve_alike_are_duplicates(log):
    world = World(log, name_key=lambda name: '/' + name.lstrip('/'))
    with pytest.raises(TurtlesimError, match='already exists'):
        world.spawn('/turtle1', 1, 1, 0)


def test_killing_an_unknown_turtle_fails(world):
    with pytest.raises(TurtlesimError, match=r'^Tried to kill turtle \[nemo\], which does not exist$'):
        world.kill('nemo')


def test_requests_for_unknown_turtles_fail(world, clock):
    for request in (lambda: world.command_velocity('nemo', 1, 0, 0, clock.now),
                    lambda: world.set_pen('nemo', 1, 1, 1, 1, 0),
                    lambda: world.teleport_absolute('nemo', 1, 1, 0),
                    lambda: world.teleport_relative('nemo', 1, 0)):
        with pytest.raises(TurtlesimError, match=r'There is no turtle named \[nemo\]'):
            request()


# --- bad numbers ---
@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_numbers_are_rejected_and_change_nothing(world, clock, bad):
    with pytest.raises(TurtlesimError, match='must be a finite number'):
        world.spawn('', bad, 1, 0)
    with pytest.raises(TurtlesimError, match=r'Cannot teleport \[turtle1\]: theta=.* must be a finite number'):
        world.teleport_absolute('turtle1', 1, 1, bad)
    with pytest.raises(TurtlesimError, match=r'linear=.* must be a finite number'):
        world.teleport_relative('turtle1', bad, 0)
    world.command_velocity('turtle1', 1.0, 0.0, 0.0, clock.now)
    with pytest.raises(TurtlesimError, match=r'Ignoring a velocity command for \[turtle1\]: angular.z='):
        world.command_velocity('turtle1', 0.0, 0.0, bad, clock.now)
    clock.run(world, 10)
    assert_pose(world, CENTRE + 0.16, CENTRE, 0.0)
    assert [turtle.name for turtle in world.turtles()] == ['turtle1']
    assert world.spawn('', 1, 1, 0) == 'turtle2'  # the failed spawn used no number of the counter


def test_updates_run_in_name_order(world, clock):
    """A turtle updated earlier in the tick paints before a later one reads its colour."""
    world.spawn('zed', 3.0, 3.0, 0.0)
    world.spawn('abe', 1.0, 3.0, 0.0)
    world.set_pen('abe', 250, 0, 0, 3, 0)
    clock.run(world, 1)
    world.teleport_absolute('abe', 3.0, 3.0, 0.0)  # abe draws a line ending under zed
    clock.run(world, 1)
    assert world.turtle('zed').color == (250, 0, 0)


def test_a_resting_turtle_before_the_painter_in_name_order_senses_its_line_a_tick_later(world, clock):
    """As in the original, each turtle reads the canvas at its turn in the tick."""
    world.spawn('abe', 3.0, 3.0, 0.0)  # stays where it is
    world.spawn('zed', 1.0, 3.0, 0.0)
    world.set_pen('zed', 250, 0, 0, 3, 0)
    clock.run(world, 3)
    world.teleport_absolute('zed', 3.0, 3.0, 0.0)  # zed draws a line ending under abe
    clock.run(world, 1)
    assert world.turtle('abe').color == DEFAULT_BACKGROUND
    clock.run(world, 1)
    assert world.turtle('abe').color == (250, 0, 0)


def _state(world):
    return [(turtle.name, turtle.x, turtle.qt_y, turtle.theta, turtle.color) for turtle in world.turtles()]


def test_ticks_that_skip_the_resting_turtles_give_what_visiting_every_turtle_gives(clock):
    """A tick visits the resting turtles only when the canvas changed under them; a world made to
    visit every turtle at every tick, given the same random requests, stays identical."""
    import random
    rng = random.Random(24)
    worlds = [World(RecordingLog(), rng=random.Random(1)) for _ in range(2)]
    for world in worlds:
        for index in range(30):
            world.spawn('t%02d' % index, 0.5 + index * 0.35, 0.5 + (index % 7) * 1.5, 0.0)
            world.set_pen('t%02d' % index, 0, 0, 0, 0, index % 2)  # half of them draw
    for tick in range(600):
        name = 't%02d' % rng.randrange(30)
        choice = rng.random()
        for world in worlds:
            request = random.Random(tick)
            if choice < 0.02:
                world.command_velocity(name, request.uniform(-2, 2), 0.0, request.uniform(-3, 3), clock.now)
            elif choice < 0.08:  # a line ending under another turtle
                target = world.turtle('t%02d' % request.randrange(30))
                world.teleport_absolute(name, target.x, target.y, 0.0)
            elif choice < 0.1:
                world.set_pen(name, 10 * (tick % 25), 0, 0, 1 + tick % 4, tick % 3 == 0)
            elif choice < 0.105:
                world.clear((tick % 256, 0, 0))
        worlds[1]._sensed_version = None  # noqa: SLF001 - the tick then visits every turtle
        for world in worlds:
            world.tick(clock.now)
        clock.now += TICK_SECONDS
        assert _state(worlds[0]) == _state(worlds[1])
        assert (worlds[0].canvas.pixels == worlds[1].canvas.pixels).all()
