"""What each key does in the TurtleBot3 keyboard teleop (pure logic: no rospy, no terminal).

w/x change the target linear velocity by 0.01 m/s, a/d the target angular velocity by 0.1 rad/s,
space or s stop the robot at once, Ctrl-C quits. The velocity actually sent moves toward the target
by at most 0.005 m/s and 0.05 rad/s per publishing pass, so the robot speeds up smoothly.
"""

# Largest speeds of the real robots (m/s, rad/s): the teleop never asks for more.
SPEED_LIMITS = {
    'burger': (0.22, 2.84),
    'waffle': (0.26, 1.82),
    'waffle_pi': (0.26, 1.82),
}
DEFAULT_MODEL = 'burger'

LINEAR_KEY_STEP = 0.01
ANGULAR_KEY_STEP = 0.1
LINEAR_RAMP_STEP = 0.005
ANGULAR_RAMP_STEP = 0.05

VELOCITY_KEYS = {
    'w': (LINEAR_KEY_STEP, 0.0),
    'x': (-LINEAR_KEY_STEP, 0.0),
    'a': (0.0, ANGULAR_KEY_STEP),
    'd': (0.0, -ANGULAR_KEY_STEP),
}
STOP_KEYS = (' ', 's')
QUIT_KEY = '\x03'  # Ctrl-C: in raw mode the terminal sends it as a byte instead of a signal
KEYS_BETWEEN_BANNERS = 20


def speed_limits(model):
    """(max linear m/s, max angular rad/s, known) for a model name; unknown models get burger's."""
    if model in SPEED_LIMITS:
        return SPEED_LIMITS[model] + (True,)
    return SPEED_LIMITS[DEFAULT_MODEL] + (False,)


def _clamp(value, limit):
    return max(-limit, min(limit, value))


def _approach(current, target, step):
    if current < target:
        return min(target, current + step)
    return max(target, current - step)


class KeyCommands:
    """Turns key presses into target velocities, and targets into a smooth ramp of commands."""

    def __init__(self, max_linear, max_angular):
        self.max_linear = max_linear
        self.max_angular = max_angular
        self.target_linear = 0.0
        self.target_angular = 0.0
        self.linear = 0.0   # what is being sent now, ramping toward the target
        self.angular = 0.0
        self.quit = False
        self._velocity_keys_since_banner = 0

    def banner(self):
        return '\n'.join([
            'Control Your TurtleBot3!',
            '---------------------------',
            'Moving around:',
            '        w',
            '   a    s    d',
            '        x',
            '',
            'w/x : increase/decrease linear velocity (limit %.2f m/s)' % self.max_linear,
            'a/d : increase/decrease angular velocity (limit %.2f rad/s)' % self.max_angular,
            'space key, s : force stop',
            '',
            'CTRL-C to quit',
        ])

    def status(self):
        return 'currently:\tlinear vel %.2f\t angular vel %.2f' % (self.target_linear,
                                                                   self.target_angular)

    def press(self, key):
        """Apply one key; returns the text to show the user, or None for keys that do nothing."""
        if key == QUIT_KEY:
            self.quit = True
            self._stop()
            return None
        if key in STOP_KEYS:
            self._stop()
            return self.status()
        if key not in VELOCITY_KEYS:
            return None
        linear_step, angular_step = VELOCITY_KEYS[key]
        # Rounded so that 22 presses of w give exactly 0.22, not 0.21999999999999997.
        self.target_linear = round(_clamp(self.target_linear + linear_step, self.max_linear), 3)
        self.target_angular = round(_clamp(self.target_angular + angular_step, self.max_angular), 3)
        self._velocity_keys_since_banner += 1
        if self._velocity_keys_since_banner == KEYS_BETWEEN_BANNERS:
            self._velocity_keys_since_banner = 0
            return self.banner() + '\n' + self.status()
        return self.status()

    def ramp(self):
        """One publishing pass: move the sent velocities toward the targets; returns (linear, angular)."""
        self.linear = _approach(self.linear, self.target_linear, LINEAR_RAMP_STEP)
        self.angular = _approach(self.angular, self.target_angular, ANGULAR_RAMP_STEP)
        return self.linear, self.angular

    def _stop(self):
        self.target_linear = self.target_angular = 0.0
        self.linear = self.angular = 0.0
