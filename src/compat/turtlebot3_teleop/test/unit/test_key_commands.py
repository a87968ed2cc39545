"""The TurtleBot3 teleop's keys, fed one by one to the pure logic."""
import pytest

from turtlebot3_teleop.key_commands import KeyCommands, speed_limits


def burger():
    return KeyCommands(*speed_limits('burger')[:2])


def press_all(commands, keys):
    return [commands.press(key) for key in keys]


@pytest.mark.parametrize('model, limits', [
    ('burger', (0.22, 2.84, True)),
    ('waffle', (0.26, 1.82, True)),
    ('waffle_pi', (0.26, 1.82, True)),
    ('rover', (0.22, 2.84, False)),
    ('', (0.22, 2.84, False)),
])
def test_limits_follow_the_model_and_unknown_models_get_burgers(model, limits):
    assert speed_limits(model) == limits


def test_w_x_a_d_step_the_targets():
    commands = burger()
    press_all(commands, 'www')
    assert commands.target_linear == 0.03
    press_all(commands, 'x')
    assert commands.target_linear == 0.02
    press_all(commands, 'aaa')
    assert commands.target_angular == pytest.approx(0.3)
    press_all(commands, 'dddd')
    assert commands.target_angular == pytest.approx(-0.1)


@pytest.mark.parametrize('model, presses, linear, angular', [
    ('burger', 30, 0.22, 2.84),
    ('waffle', 40, 0.26, 1.82),
])
def test_targets_stop_at_the_models_limits(model, presses, linear, angular):
    commands = KeyCommands(*speed_limits(model)[:2])
    press_all(commands, 'w' * presses + 'a' * presses)
    assert (commands.target_linear, commands.target_angular) == (linear, angular)
    press_all(commands, 'x' * 2 * presses + 'd' * 2 * presses)
    assert (commands.target_linear, commands.target_angular) == (-linear, -angular)


def test_each_key_prints_the_targets():
    commands = burger()
    assert press_all(commands, 'wwa') == [
        'currently:\tlinear vel 0.01\t angular vel 0.00',
        'currently:\tlinear vel 0.02\t angular vel 0.00',
        'currently:\tlinear vel 0.02\t angular vel 0.10',
    ]


def test_other_keys_do_nothing():
    commands = burger()
    commands.press('w')
    assert press_all(commands, 'qk1\x1b[A') == [None] * 6
    assert commands.target_linear == 0.01 and not commands.quit


def test_the_banner_names_the_keys_and_the_limits():
    banner = KeyCommands(*speed_limits('waffle')[:2]).banner()
    assert banner.startswith('Control Your TurtleBot3!')
    for text in ('        w\n   a    s    d\n        x', '0.26 m/s', '1.82 rad/s',
                 'space key, s : force stop', 'CTRL-C to quit'):
        assert text in banner


def test_the_banner_comes_again_after_every_20_velocity_keys():
    commands = burger()
    printed = press_all(commands, 'wxwx ' + 'wa' * 30)
    with_banner = [i for i, text in enumerate(printed) if text.startswith('Control Your TurtleBot3!')]
    # the stop key (index 4) does not count: velocity keys number 20, 40 and 60 are at those indices
    assert with_banner == [20, 40, 60]
    assert printed[20].split('\n')[-1].startswith('currently:\tlinear vel')


def test_the_sent_velocity_ramps_toward_the_target():
    commands = burger()
    press_all(commands, 'w' * 3 + 'a' * 2)
    passes = [commands.ramp() for _ in range(8)]
    linears = [round(linear, 4) for linear, _ in passes]
    angulars = [round(angular, 4) for _, angular in passes]
    assert linears == [0.005, 0.01, 0.015, 0.02, 0.025, 0.03, 0.03, 0.03]
    assert angulars == [0.05, 0.1, 0.15, 0.2, 0.2, 0.2, 0.2, 0.2]
    press_all(commands, 'xxxxxx')  # target -0.03: ramps down through zero
    assert [round(commands.ramp()[0], 4) for _ in range(3)] == [0.025, 0.02, 0.015]


@pytest.mark.parametrize('key', [' ', 's'])
def test_space_and_s_stop_at_once(key):
    commands = burger()
    press_all(commands, 'wwwwaa')
    for _ in range(5):
        commands.ramp()
    assert commands.press(key) == 'currently:\tlinear vel 0.00\t angular vel 0.00'
    assert commands.ramp() == (0.0, 0.0)


def test_ctrl_c_quits_and_zeroes_everything():
    commands = burger()
    press_all(commands, 'wwa')
    commands.ramp()
    assert commands.press('\x03') is None
    assert commands.quit
    assert commands.ramp() == (0.0, 0.0)
