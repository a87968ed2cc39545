"""What the TurtleBot2 keyboard teleop's keys mean, without ROS and without a terminal.

The teleop works in passes of 0.1 s: keys pressed during a pass change the target (a direction
times the current speeds); at the end of each pass the sent velocity moves toward the target by at
most one step, so the robot speeds up and slows down smoothly.
"""

# key: (linear, angular) direction, multiplied by the current speed and turn.
MOVE_KEYS = {
    'u': (1, 1), 'i': (1, 0), 'o': (1, -1),
    'j': (0, 1), 'l': (0, -1),
    'm': (-1, -1), ',': (-1, 0), '.': (-1, 1),
}
# key: (factor for speed, factor for turn).
SPEED_KEYS = {
    'q': (1.1, 1.1), 'z': (0.9, 0.9),
    'w': (1.1, 1.0), 'x': (0.9, 1.0),
    'e': (1.0, 1.1), 'c': (1.0, 0.9),
}
FORCE_STOP_KEYS = (' ', 'k')
QUIT_KEY = '\x03'  # Ctrl-C, which a raw terminal delivers as a byte instead of SIGINT

DEFAULT_SPEED = 0.2  # m/s
DEFAULT_TURN = 1.0  # rad/s
PASS_SECONDS = 0.1
LINEAR_STEP = 0.02  # m/s per pass
ANGULAR_STEP = 0.1  # rad/s per pass
# A held key repeats; when no key came for this many passes in a row the user let go.
IDLE_PASSES_BEFORE_STOP = 4

BANNER = """Control Your Turtlebot!
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%
space key, k : force stop
anything else : stop smoothly

CTRL-C to quit"""


def _ramp(current, target, step):
    """current moved toward target by at most step."""
    if target > current:
        return min(target, current + step)
    return max(target, current - step)


class KeyCommands:
    """The state of the teleop: current speeds, the direction asked for, the velocity being sent."""

    def __init__(self, speed=DEFAULT_SPEED, turn=DEFAULT_TURN):
        self.speed = speed
        self.turn = turn
        self.linear = 0.0  # m/s, what is sent now
        self.angular = 0.0  # rad/s
        self._direction = (0, 0)
        self._idle_passes = 0
        self._key_in_this_pass = False

    def press(self, key):
        """Apply one key (a 1-character str). Returns True if it changed speed or turn."""
        self._key_in_this_pass = True
        self._idle_passes = 0
        if key in MOVE_KEYS:
            self._direction = MOVE_KEYS[key]
        elif key in SPEED_KEYS:
            speed_factor, turn_factor = SPEED_KEYS[key]
            self.speed *= speed_factor
            self.turn *= turn_factor
            return True
        elif key in FORCE_STOP_KEYS:
            self._direction = (0, 0)
            self.linear = self.angular = 0.0
        else:
            self._direction = (0, 0)
        return False

    def end_pass(self):
        """Close a 0.1 s pass: ramp toward the target. Returns (linear m/s, angular rad/s) to send."""
        if not self._key_in_this_pass:
            self._idle_passes += 1
            if self._idle_passes > IDLE_PASSES_BEFORE_STOP:
                self._direction = (0, 0)
        self._key_in_this_pass = False
        linear_direction, angular_direction = self._direction
        self.linear = _ramp(self.linear, self.speed * linear_direction, LINEAR_STEP)
        self.angular = _ramp(self.angular, self.turn * angular_direction, ANGULAR_STEP)
        return self.linear, self.angular

    def speeds_line(self):
        """The line printed at start and after every speed key."""
        return 'currently:\tspeed %g\tturn %g' % (self.speed, self.turn)
