"""The TurtleBot3 checks on made-up odometry, scans and commands: a circle through the spawn pose
or off it, commands kept or not, a stop in the band or not, a robot that stays or creeps."""
import math

from sensor_msgs.msg import LaserScan

from course_checks import driving
from course_checks.verdict import decimal


def circle_poses(radius, centre, seconds=10.0, step=0.1):
    """(sim time, x, y, yaw) round a circle counter-clockwise, starting below its centre."""
    poses = []
    for i in range(int(seconds / step)):
        angle = i * step - math.pi / 2
        poses.append((i * step, centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle), 0.0))
    return poses


def test_a_circle_through_the_spawn_pose_passes():
    verdict = driving.circle_through(circle_poses(1.0, (0.0, 1.0)), 1.0, (0.0, 0.0), 0.05, 0.1)
    assert verdict.passed and 'a circle of radius 1.000 m centred at (0.00, 1.00)' in verdict.reason


def test_a_circle_elsewhere_or_of_another_radius_fails():
    assert not driving.circle_through(circle_poses(1.0, (0.0, 1.5)), 1.0, (0.0, 0.0), 0.05, 0.1).passed
    wide = driving.circle_through(circle_poses(1.2, (0.0, 1.2)), 1.0, (0.0, 0.0), 0.05, 0.1)
    assert not wide.passed and 'radius 1.200 m' in wide.reason


def test_a_robot_that_hardly_moved_drove_no_circle():
    poses = [(t, 0.001 * t, 0.0, 0.0) for t in range(20)]
    verdict = driving.circle_through(poses, 1.0, (0.0, 0.0), 0.05, 0.1)
    assert not verdict.passed and verdict.reason == 'the robot moved 0.02 m in 19 simulated seconds'


def test_commands_kept_at_their_rate_and_values():
    commands = [(float(t), 1.0, 1.0) for t in range(10)]
    assert driving.commands_kept(commands, 10.0, 1.0, 1.0, 0.01, 1.0, 0.1).passed
    fast = driving.commands_kept([(t / 2, 1.0, 1.0) for t in range(20)], 10.0, 1.0, 1.0, 0.01, 1.0, 0.1)
    assert not fast.passed and fast.reason == '20 messages in 10.0 simulated seconds, 2.00 Hz'
    wrong = driving.commands_kept(commands[:5] + [(5.0, 0.5, 1.0)], 6.0, 1.0, 1.0, 0.01, 1.0, 0.1)
    assert not wrong.passed and wrong.reason.endswith('among them linear.x 0.5, angular.z 1')
    assert not driving.commands_kept(commands[:1], 10.0, 1.0, 1.0, 0.01, 1.0, 0.1).passed


def test_stopped_for_a_while_of_simulated_time():
    driving_then_standing = [(t / 10, min(t, 20) * 0.05, 0.0, 0.0) for t in range(40)]
    assert driving.stopped_for(driving_then_standing, 1.0)
    assert not driving.stopped_for(driving_then_standing, 2.0)
    assert not driving.stopped_for(driving_then_standing[:22], 1.0)   # not yet standing that long


def test_the_stop_is_the_first_pose_of_the_latest_standing_still():
    # Drove to 1 m, stood, crept 0.1 m at 3 s, stood again: the stop is where it stood last.
    poses = [(t / 10, min(t, 20) * 0.05 + (0.1 if t >= 30 else 0.0), 0.0, 0.0) for t in range(50)]
    assert driving.still_since(poses) == (3.0, 1.1, 0.0, 0.0)
    assert driving.still_since(poses[:30]) == (2.0, 1.0, 0.0, 0.0)
    assert driving.still_since(poses[:1]) == poses[0]


def test_driving_off_is_the_first_pose_away_from_where_the_robot_was_put():
    # Stood at 2 m until 5 s, put back to 1.5 m at 5.0 s (the odometry of 4.9 s still shows 2 m),
    # stood there until 5.5 s, then drove.
    poses = [(t / 10, 2.0 if t <= 49 else 1.5 + max(0, t - 55) * 0.05, 0.0, 0.0) for t in range(70)]
    assert driving.drove_off(poses, 5.0, (1.5, 0.0)) == 5.6
    assert driving.drove_off(poses[:56], 5.0, (1.5, 0.0)) is None
    assert driving.drove_off(poses, 7.0, (1.5, 0.0)) is None   # only the poses after the put-back


def scans(*fronts):
    return [LaserScan(ranges=[front] + [3.5] * 359) for front in fronts]


def test_the_front_beam_at_the_stop_is_the_median_over_the_stay():
    verdict = driving.front_at_stop(scans(*([0.45] * 20 + [0.6])), 5, 0.35, 0.5)
    assert verdict.passed and verdict.reason == 'stopped with the front beam at 0.450 m (median over the stop)'
    assert not driving.front_at_stop(scans(*([0.9] * 25)), 5, 0.35, 0.5).passed


def test_staying_means_no_collision_and_at_most_the_creep():
    still = [(t / 10, 1.0, 0.0, 0.0) for t in range(51)]
    assert driving.stayed(still, 0, 0.11, 5).reason == '0 collisions, 0.000 m moved in 5.0 s'
    assert driving.stayed(still, 0, 0.11, 5).passed
    assert not driving.stayed(still, 1, 0.11, 5).passed
    creeping = [(t / 10, 1.0 + t * 0.01, 0.0, 0.0) for t in range(51)]
    assert not driving.stayed(creeping, 0, 0.11, 5).passed
    assert not driving.stayed(still[:30], 0, 0.11, 5).passed   # watched 2.9 s of 5


def test_a_centre_at_zero_is_written_without_a_minus_sign_whatever_the_fit_rounds_to():
    assert [decimal(value, 2) for value in (-1e-17, 0.0, -0.004, -0.05, -10.0, 3.14159)] == \
        ['0.00', '0.00', '0.00', '-0.05', '-10.00', '3.14']
    mirrored = driving.circle_through(circle_poses(1.0, (-1e-12, 1.0)), 1.0, (0.0, 0.0), 0.05, 0.1)
    assert 'centred at (0.00, 1.00)' in mirrored.reason
