"""The core's scans and odometry to the last bit: a fixed drive (straight runs, spins, arcs, fast
runs into walls) in every world, and five robots seeing each other, against what the core
produced before it was made faster (data/golden_runs.npz).

The recorded floats are those of numpy's trigonometry on the machine that recorded them (numpy
1.24, AVX-512: its sin and cos differ from libm's in the last bit). Where this numpy's functions
give other bits for the same inputs (data/golden_runs.npz keeps a sample of inputs and results),
no core could reproduce the recorded bits: there the runs are compared to within 1e-6.

To record again (only ever from a core known to be right):
    /usr/bin/python3 src/fake_tb3/test/unit/test_golden_runs.py
"""
import logging
import os

import numpy as np

from fake_tb3.lidar import Laser
from fake_tb3.models import get_model
from fake_tb3.simulation import SimRobot, Simulation
from fake_tb3.world import World, load_world

GOLDEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'data', 'golden_runs.npz')
DT = 0.01
STEPS = 400
SCAN_EVERY = 50  # physics steps between two scans (the 5 Hz scan of the 100 Hz physics: 20)
# (linear m/s, angular rad/s), each held for STEPS / len(COMMANDS) steps: slow and fast, into
# walls and out of contacts.
COMMANDS = [(0.22, 0.0), (0.0, 2.84), (1.5, 0.3), (-0.2, -1.0), (0.2, 1.0), (3.0, 0.0),
            (-0.22, 0.5), (0.0, -2.84), (0.1, 4.0), (5.0, -2.0)]
SPAWNS = {'empty': (0.0, 0.0, 0.0), 'corridor': (0.0, 0.0, 0.3), 'wall_ahead': (1.5, 0.0, 0.0),
          'turtlebot3_world': (-2.0, -0.5, 0.0)}
WORLDS = sorted(SPAWNS)
# Five robots 0.35 m apart in a row, heading every way: they see and hit each other, and
# (four or more free) step together.
CROWD = [(0.35 * index, 0.0, 1.3 * index) for index in range(5)]


def _quiet_log():
    log = logging.getLogger('fake_tb3.golden_runs')
    log.addHandler(logging.NullHandler())
    log.propagate = False
    return log


def drive(world, spawns):
    """{'poses': (STEPS, robots, 7) x, y, yaw, linear, angular, left and right wheel angles after
    each step, 'scans': (STEPS / SCAN_EVERY, robots, 360) ranges, 'collisions': (robots,)}."""
    robots = [SimRobot('r%d' % index, get_model('waffle' if index % 2 else 'burger'), *spawn,
                       Laser(noise_stddev=0.01, seed=index)) for index, spawn in enumerate(spawns)]
    simulation = Simulation(world, robots, log=_quiet_log())
    poses, scans = [], []
    hold = STEPS // len(COMMANDS)
    for step in range(STEPS):
        if step % hold == 0:
            linear, angular = COMMANDS[step // hold]
            for index, robot in enumerate(robots):
                simulation.command(robot, linear * (1 - 0.1 * index), angular)
        if step % SCAN_EVERY == 0:
            scans.append(simulation.scans())
        simulation.step(DT)
        poses.append([robot.pose + robot.velocity + robot.wheel_angles for robot in robots])
    return {'poses': np.array(poses), 'scans': np.array(scans),
            'collisions': np.array([robot.collisions for robot in robots])}


def runs():
    """Every run of this test: one robot in each world, and the crowd in the empty world."""
    result = {}
    for name in WORLDS:
        for key, value in drive(load_world(name), [SPAWNS[name]]).items():
            result['%s.%s' % (name, key)] = value
    for key, value in drive(World('crowd'), CROWD).items():
        result['crowd.%s' % key] = value
    return result


def probes():
    """numpy's results for a sample of the inputs the core gives its functions."""
    inputs = np.random.default_rng(0).uniform(-7.0, 7.0, 512)
    return {'probe.sin': np.sin(inputs), 'probe.cos': np.cos(inputs),
            'probe.arctan2': np.arctan2(inputs, inputs[::-1]),
            'probe.arcsin': np.arcsin(inputs / 7),
            'probe.sinc': np.sinc(inputs), 'probe.hypot': np.hypot(inputs, inputs[::-1])}


def _same_bits(first, second):
    return first.shape == second.shape and first.tobytes() == second.tobytes()


def test_scans_and_odometry_are_those_recorded():
    golden = np.load(GOLDEN)
    exact = all(_same_bits(value, golden[key]) for key, value in probes().items())
    for key, value in runs().items():
        expected = golden[key]
        if exact or key.endswith('collisions'):
            # tobytes: inf and nan compare too, and -0.0 differs from 0.0.
            assert _same_bits(value, expected), '%s differs from the recorded run' % key
        else:
            np.testing.assert_allclose(value, expected, rtol=0, atol=1e-6, err_msg=key)


if __name__ == '__main__':
    os.makedirs(os.path.dirname(GOLDEN), exist_ok=True)
    np.savez_compressed(GOLDEN, **runs(), **probes())
    print('%s: %d bytes' % (GOLDEN, os.path.getsize(GOLDEN)))
