"""The settings turtlesim_node takes on its command line, where no other node can change them: a
parameter can be set by any node before turtlesim reads it (a student's launch file beside the
grader's turtlesim, say). Pure: no rospy."""
import math

# option: (setting, type); a flag takes no value.
OPTIONS = {
    '--real-time-factor': ('real_time_factor', float),
    '--clock-rate': ('clock_rate', float),
    '--lock-step': ('lock_step', bool),
    '--canvas-png': ('canvas_png', str),
}


def settings(argv):
    """{setting: value} of the options in argv (the arguments rospy.myargv leaves, without the
    program's name): `--real-time-factor F` (simulated seconds per wall second: on a simulated
    clock whatever /use_sim_time says, the clock's settings read from here, not from parameters),
    `--clock-rate HZ`, `--lock-step`, `--canvas-png PATH` (also as --option=value). Other arguments
    are ignored, as the original ignores them. ValueError names a bad one."""
    found = {}
    args = list(argv)
    while args:
        arg = args.pop(0)
        option, equals, value = arg.partition('=')
        if option not in OPTIONS:
            continue
        name, kind = OPTIONS[option]
        if kind is bool:
            if equals:
                raise ValueError('%s takes no value, got %r' % (option, arg))
            found[name] = True
            continue
        if not equals:
            if not args:
                raise ValueError('%s needs a value' % option)
            value = args.pop(0)
        if kind is float:
            try:
                number = float(value)
            except ValueError:
                number = math.nan
            if not (math.isfinite(number) and number > 0):
                raise ValueError('%s must be a positive number, got %r' % (option, value))
            value = number
        found[name] = value
    if ('clock_rate' in found or 'lock_step' in found) and 'real_time_factor' not in found:
        raise ValueError('--clock-rate and --lock-step go with --real-time-factor')
    return found
