"""The teleop's key logic, fed key by key and pass by pass."""
import pytest

from turtlebot_teleop.key_commands import BANNER, MOVE_KEYS, KeyCommands


def run_passes(commands, count, key=None):
    """count passes, pressing `key` in each if given; returns the velocities sent after the last."""
    sent = None
    for _ in range(count):
        if key is not None:
            commands.press(key)
        sent = commands.end_pass()
    return sent


def test_still_before_any_key():
    assert run_passes(KeyCommands(), 3) == (0.0, 0.0)


@pytest.mark.parametrize('key, direction', [
    ('i', (1, 0)), ('o', (1, -1)), ('j', (0, 1)), ('l', (0, -1)),
    ('u', (1, 1)), (',', (-1, 0)), ('.', (-1, 1)), ('m', (-1, -1)),
])
def test_held_move_key_reaches_default_speeds(key, direction):
    linear, angular = run_passes(KeyCommands(), 20, key)
    assert linear == pytest.approx(0.2 * direction[0])
    assert angular == pytest.approx(1.0 * direction[1])


def test_ramps_by_one_step_per_pass():
    commands = KeyCommands()
    sent = [run_passes(commands, 1, 'u') for _ in range(12)]
    assert [linear for linear, _ in sent][:3] == pytest.approx([0.02, 0.04, 0.06])
    assert [angular for _, angular in sent][:3] == pytest.approx([0.1, 0.2, 0.3])
    assert sent[9] == pytest.approx((0.2, 1.0))  # 10 passes (1 s) to full speed
    assert sent[11] == pytest.approx((0.2, 1.0))  # and no further


def test_let_go_stops_smoothly_after_four_idle_passes():
    commands = KeyCommands()
    run_passes(commands, 10, 'i')
    assert [run_passes(commands, 1)[0] for _ in range(4)] == pytest.approx([0.2] * 4)
    assert run_passes(commands, 1)[0] == pytest.approx(0.18)  # the 5th idle pass starts to slow down
    assert run_passes(commands, 9)[0] == pytest.approx(0.0)


@pytest.mark.parametrize('stop_key', [' ', 'k'])
def test_stop_keys_stop_at_once(stop_key):
    commands = KeyCommands()
    run_passes(commands, 10, 'u')
    assert run_passes(commands, 1, stop_key) == (0.0, 0.0)


@pytest.mark.parametrize('other_key', ['a', '1', '\x1b', 'I'])
def test_other_keys_stop_smoothly(other_key):
    commands = KeyCommands()
    run_passes(commands, 10, 'u')
    assert run_passes(commands, 1, other_key) == pytest.approx((0.18, 0.9))
    assert run_passes(commands, 10) == (0.0, 0.0)


@pytest.mark.parametrize('key, speed, turn', [
    ('q', 0.22, 1.1), ('z', 0.18, 0.9),
    ('w', 0.22, 1.0), ('x', 0.18, 1.0),
    ('e', 0.2, 1.1), ('c', 0.2, 0.9),
])
def test_speed_keys_scale_by_ten_percent(key, speed, turn):
    commands = KeyCommands()
    assert commands.press(key) is True
    assert (commands.speed, commands.turn) == pytest.approx((speed, turn))


def test_speed_key_changes_target_while_moving():
    commands = KeyCommands()
    run_passes(commands, 10, 'i')
    commands.press('q')
    assert run_passes(commands, 2, 'i') == pytest.approx((0.22, 0.0))


def test_move_keys_do_not_report_a_speed_change():
    commands = KeyCommands()
    assert not any(commands.press(key) for key in list(MOVE_KEYS) + [' ', 'k', 'a'])


def test_speeds_line_as_the_slide_prints_it():
    commands = KeyCommands()
    assert commands.speeds_line() == 'currently:\tspeed 0.2\tturn 1'
    commands.press('q')
    assert commands.speeds_line() == 'currently:\tspeed 0.22\tturn 1.1'


def test_banner_shows_the_layout():
    assert BANNER.startswith('Control Your Turtlebot!')
    for row in ('u    i    o', 'j    k    l', 'm    ,    .'):
        assert row in BANNER
    assert 'CTRL-C to quit' in BANNER
