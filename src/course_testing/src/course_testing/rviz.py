"""rviz started on a virtual screen until it draws, once more if a signal killed it at its start.

rviz's software OpenGL set-up has been seen to crash (SIGSEGV, right after its line "Forcing OpenGl
version 0.") now and then: at the first start on a fresh machine (the tour, whose second start
drew), and in CI's host run (the slides' rviz rostest, which then waited out its 90 s). Whoever
waits for rviz's pictures (the rviz rostests, the tour's rviz lab) sees its launch end at once,
starts it once more when a signal killed it, and says so; an rviz that exits by itself, or is
killed twice, fails at once with what its launch printed.
"""
import re
import signal

from course_common.waiting import wait_until

from course_testing.screen import red_pixels, uncovered_pixels

# roslaunch's line when a node it started ends (a REQUIRED one ends the launch): its exit code, then
# its command line, which names the node (__name:=rviz).
NODE_DIED = re.compile(r'process has died \[pid \d+, exit code (-?\d+), cmd ([^\n]*)')

STARTS = ('first', 'second')

# rviz's window fills the screen (its config's Window Geometry is the screen's size). CI's bookworm
# run once took the tour's picture with 36 % of the screen black, the laser points already red: a
# screenshot taken before the window had its size, or mid-frame. Such a screenshot is taken again.
UNCOVERED_AT_MOST = 0.01  # of the screen


def what_the_screen_shows(path):
    """(laser-red pixels, uncovered pixels, a sentence saying both) of a screenshot."""
    red = red_pixels(path)
    uncovered, box = uncovered_pixels(path)
    where = ' from (%d, %d) to (%d, %d)' % box if box else ''
    return red, uncovered, '%d laser-red pixels, %d uncovered (black)%s' % (red, uncovered, where)


def killed_by(launch_output, node):
    """The signal's name (SIGSEGV) when roslaunch says that `node` of this launch was killed by one,
    else None (still running, an exit of its own, or another node that died)."""
    for code, command in NODE_DIED.findall(launch_output):
        if int(code) < 0 and re.search(r'(^|\s)__name:=%s(\s|\]|$)' % re.escape(node), command):
            try:
                return signal.Signals(-int(code)).name
            except ValueError:
                return 'signal %d' % -int(code)
    return None


def rviz_until_drawn(start, stop, screen, screenshot, red_at_least, timeout=90.0):
    """Starts rviz's launch with `start()` and waits until a screenshot of `screen` (written to
    `screenshot`) has more than `red_at_least` laser-red pixels and rviz's window covers the screen.

    `start()` returns the running launch, with `exited()` and `output()` (what it printed so far);
    `stop(launch)` stops it. Returns (launch, notes): the launch that drew, still running, and a
    sentence for each start that a signal ended. Raises AssertionError, with the end of what the
    launch printed, when rviz ends by itself, is killed at both starts, or does not draw within
    `timeout` seconds of a start; none of its launches is then left running."""
    notes = []
    uncovered_at_most = UNCOVERED_AT_MOST * screen.width * screen.height

    def drawn():
        red, uncovered, _ = what_the_screen_shows(screen.screenshot(screenshot))
        return red > red_at_least and uncovered <= uncovered_at_most

    for start_name in STARTS:
        launch = start()
        try:
            # Twice a second: screenshots back to back would starve rviz's software rendering.
            wait_until(lambda: launch.exited() or drawn(), timeout,
                       'rviz to draw the laser points and fill the screen (%s start)' % start_name, poll=0.5)
        except AssertionError as late:
            output = launch.output()
            stop(launch)
            raise AssertionError('%s; the last screenshot: %s; its launch said:\n%s' % (
                late, what_the_screen_shows(screenshot)[2], output[-1500:])) from None
        if not launch.exited():
            return launch, notes
        output = launch.output()
        stop(launch)
        signal_name = killed_by(output, 'rviz')
        if signal_name is None or start_name == STARTS[-1]:
            raise AssertionError('rviz ended before it drew (%s start, %s); its launch said:\n%s' % (
                start_name, signal_name or 'not by a signal', output[-1500:]))
        notes.append('rviz was killed by %s at its %s start, before it drew: started again'
                     % (signal_name, start_name))
    raise AssertionError('not reached: the last start returns or raises')
