"""Exact odometry, wheels, collisions that stop at the contact and never tunnel, models."""
import math

import numpy as np
import pytest

from fake_tb3.kinematics import HeldStep, arc_poses, wheel_turns, wrap_angle
from fake_tb3.lidar import Laser
from fake_tb3.models import UnknownModelError, get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import World, load_world

THIN_WALL = {'type': 'polygon', 'points': [[2.0, -1.0], [2.0, 1.0], [2.0001, 1.0], [2.0001, -1.0]]}


def simulate(world, robots, seconds, dt=0.01):
    simulation = Simulation(world, robots)
    for _ in range(int(round(seconds / dt))):
        simulation.step(dt)
    return simulation


def robot(model='burger', x=0.0, y=0.0, yaw=0.0, command=(0.0, 0.0)):
    sim_robot = SimRobot('', get_model(model), x, y, yaw, Laser(noise_stddev=0.0))
    sim_robot.command = command
    return sim_robot


def test_straight_arc_and_spin_are_exact():
    straight = robot(command=(0.2, 0.0), yaw=math.pi / 6)
    simulate(World('empty'), [straight], 10.0)
    assert straight.pose == pytest.approx((2 * math.cos(math.pi / 6), 2 * math.sin(math.pi / 6),
                                           math.pi / 6), abs=1e-9)
    # 0.2 m/s and 0.4 rad/s: a circle of radius 0.5 around (0, 0.5), a quarter turn in 3.927 s.
    arc = robot(command=(0.2, 0.4))
    simulate(World('empty'), [arc], math.pi / 2 / 0.4, dt=math.pi / 2 / 0.4 / 100)
    assert arc.pose == pytest.approx((0.5, 0.5, math.pi / 2), abs=1e-9)
    spin = robot(command=(0.0, -1.0), x=1.0, y=-1.0)
    simulate(World('empty'), [spin], 1.0)
    assert spin.pose == pytest.approx((1.0, -1.0, -1.0), abs=1e-12)
    assert spin.velocity == (0.0, -1.0)


def test_arc_poses_matches_the_circle_for_any_step():
    x, y, yaw = arc_poses(0.0, 0.0, 0.0, 1.0, 2.0, np.array([0.1, 1.0, math.pi]))
    # Radius 0.5 around (0, 0.5): the point at angle 2t.
    assert x == pytest.approx(0.5 * np.sin([0.2, 2.0, 2 * math.pi]))
    assert y == pytest.approx(0.5 - 0.5 * np.cos([0.2, 2.0, 2 * math.pi]))
    assert wrap_angle(7.0) == pytest.approx(7.0 - 2 * math.pi)


def test_wheels_turn_with_the_drive():
    burger = robot(command=(0.033, 0.0))
    simulate(World('empty'), [burger], 1.0)
    assert burger.wheel_angles == pytest.approx((1.0, 1.0))  # 0.033 m on a 0.033 m wheel
    spinner = robot(command=(0.0, 1.0))
    simulate(World('empty'), [spinner], 1.0)
    # Turning 1 rad on the spot: each wheel rolls 0.08 m (half the 0.160 m separation).
    assert spinner.wheel_angles == pytest.approx((-0.08 / 0.033, 0.08 / 0.033))


@pytest.mark.parametrize('speed', [0.3, 100.0, 1e4])
def test_no_tunnelling_through_a_thin_wall(speed):
    world = World('thin', [THIN_WALL])
    fast = robot(command=(speed, 0.0))
    simulate(world, [fast], 10.0, dt=0.05)
    front = fast.x - 0.032 + 0.07
    assert 2.0 - 0.001 < front <= 2.0  # stopped at the wall, touching it
    assert fast.collisions == 1 and fast.in_contact
    assert fast.velocity[0] == pytest.approx(0.0, abs=1e-3 * speed)


def test_spinning_into_a_corner_is_stopped():
    # A waffle (corner radius 0.25) next to a pillar that only its turning corners can reach.
    # Its body spans x in [-0.197, 0.069], y in [-0.133, 0.133]; the pillar's disc is 0.2 m away,
    # beyond the front corners (0.151 m) but within reach of the back ones (0.2377 m). Turning
    # left, the back-right corner (at 214.03 deg) meets the disc when its distance to (0, 0.3) is
    # 0.1: cos(phi - 90) = (0.2377^2 + 0.3^2 - 0.1^2) / (2 * 0.2377 * 0.3) -> phi = 73.15 deg,
    # after turning 219.12 deg (3.8244 rad). The back side may touch a little earlier.
    waffle = robot('waffle', command=(0.0, 3.0))
    pillar = {'type': 'circle', 'center': [0.0, 0.30], 'radius': 0.1}
    simulation = simulate(World('pillar', [pillar]), [waffle], 2.0)
    assert waffle.collisions == 1
    assert 3.80 < waffle.yaw + 2 * math.pi <= 3.8245
    assert not simulation.overlapping(waffle)


def test_a_contact_counts_once_and_backing_off_ends_it():
    corridor = load_world('corridor')
    bot = robot(command=(0.5, 0.0))
    simulation = simulate(corridor, [bot], 12.0)
    assert bot.collisions == 1 and bot.x == pytest.approx(5.0 - 0.038, abs=1e-3)
    bot.command = (-0.2, 0.0)
    for _ in range(100):
        simulation.step(0.01)
    assert not bot.in_contact and bot.x == pytest.approx(5.0 - 0.038 - 0.2, abs=2e-3)
    bot.command = (0.5, 0.0)
    for _ in range(100):
        simulation.step(0.01)
    assert bot.collisions == 2


def test_robots_see_and_stop_at_each_other():
    left, right = robot(x=0.0, command=(0.5, 0.0)), robot(x=1.0, yaw=math.pi)
    simulation = Simulation(World('empty'), [left, right])
    # Facing each other: right's body spans x = 1.032 - 0.07 ... the front faces are at 0.038
    # ahead of each base: the gap is 1 - 2 * 0.038 = 0.924; left's laser at -0.032 sees the
    # other's front face at 1 - 0.038 + 0.032 = 0.994.
    assert simulation.scan(left)[0] == pytest.approx(0.994)
    for _ in range(300):
        simulation.step(0.01)
    assert left.collisions == 1 and left.x == pytest.approx(0.924, abs=1e-3)


def test_unknown_model_is_a_clear_error():
    assert get_model('waffle_pi').wheel_separation == 0.287
    assert get_model('burger').max_angular == 2.84
    assert get_model('waffle').clamp(1.0, -5.0) == (0.26, -1.82)
    assert get_model('burger').clamp(-0.1, 0.5) == (-0.1, 0.5)
    with pytest.raises(UnknownModelError, match="unknown TurtleBot3 model 'burgerr': use one of "
                                                'burger, waffle, waffle_pi'):
        get_model('burgerr')
    with pytest.raises(UnknownModelError):
        get_model(None)


def test_held_steps_are_arc_poses_to_the_last_bit():
    """HeldStep (the physics' step) against arc_poses, wrap_angle and wheel_turns, step by step,
    for straight runs, spins, arcs and a yaw set back between steps."""
    model = get_model('burger')
    random = np.random.default_rng(3)
    for linear, angular in [(0.22, 0.0), (0.0, 2.84), (-1.5, 0.3), (3.0, -7.0), (1e-9, 1e-12)]:
        duration = float(random.choice([0.01, 0.013, 0.001]))
        held = HeldStep((linear, angular), duration, model)
        x, y, yaw = random.uniform(-3, 3, 2).tolist() + [float(random.uniform(-math.pi, math.pi))]
        for step in range(200):
            if step == 150:
                yaw = 1.0  # a pose moved by something else: planned again from there
            expected = arc_poses(x, y, yaw, linear, angular, duration)
            x, y, yaw = held.pose_after(x, y, yaw)
            assert (x, y, yaw) == (float(expected[0]), float(expected[1]),
                                   wrap_angle(float(expected[2])))
        assert (held.left, held.right) == wheel_turns(linear * duration, angular * duration, model)
