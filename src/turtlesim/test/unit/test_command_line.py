"""turtlesim_node's command-line settings (the grader's: no node can change them as it can a
parameter)."""
import pytest

from turtlesim.command_line import settings


def test_none_given_leaves_the_parameters_to_decide():
    assert settings([]) == {}
    assert settings(['anything', '--help-me', 'x:=y']) == {}   # ignored, as the original ignores them


def test_the_graders_settings_in_both_spellings():
    assert settings(['--real-time-factor', '5', '--lock-step', '--canvas-png', '/out/circle.png']) == {
        'real_time_factor': 5.0, 'lock_step': True, 'canvas_png': '/out/circle.png'}
    assert settings(['--real-time-factor=2.5', '--clock-rate=100', '--canvas-png=']) == {
        'real_time_factor': 2.5, 'clock_rate': 100.0, 'canvas_png': ''}


@pytest.mark.parametrize('argv, said', [
    (['--real-time-factor', '0'], "--real-time-factor must be a positive number, got '0'"),
    (['--real-time-factor', 'nan'], "--real-time-factor must be a positive number, got 'nan'"),
    (['--real-time-factor', 'inf'], "--real-time-factor must be a positive number, got 'inf'"),
    (['--real-time-factor', 'fast'], "--real-time-factor must be a positive number, got 'fast'"),
    (['--real-time-factor'], '--real-time-factor needs a value'),
    (['--real-time-factor', '5', '--lock-step=yes'], "--lock-step takes no value, got '--lock-step=yes'"),
    (['--lock-step'], '--clock-rate and --lock-step go with --real-time-factor'),
])
def test_a_bad_setting_is_named(argv, said):
    with pytest.raises(ValueError) as error:
        settings(argv)
    assert str(error.value) == said
