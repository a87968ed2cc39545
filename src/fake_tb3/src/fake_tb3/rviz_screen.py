"""Starts rviz when there is a screen to draw on, else says in one sentence what to do.

rviz without a reachable X display aborts inside Qt ("could not connect to display", exit code -6),
which tells a student nothing about the fix."""
import ctypes
import ctypes.util
import os
import sys

NO_SCREEN = ('rviz needs a screen, and %s: run this launch file in a terminal of your desktop '
             '(or over ssh -X), or without a screen under a virtual one: '
             'xvfb-run -a roslaunch turtlebot3_gazebo turtlebot3_gazebo_rviz.launch')


def screen_problem(display):
    """None when an X client can open `display`, else why not (for NO_SCREEN)."""
    if not display:
        return 'DISPLAY is not set'
    library = ctypes.util.find_library('X11')
    if library is None:
        return None  # no libX11 to ask: let rviz try and say for itself
    xlib = ctypes.CDLL(library)
    xlib.XOpenDisplay.restype = ctypes.c_void_p
    xlib.XOpenDisplay.argtypes = [ctypes.c_char_p]
    connection = xlib.XOpenDisplay(display.encode())
    if not connection:
        return 'the display DISPLAY=%s cannot be opened' % display
    xlib.XCloseDisplay.argtypes = [ctypes.c_void_p]
    xlib.XCloseDisplay(connection)
    return None


def main(argv):
    problem = screen_problem(os.environ.get('DISPLAY', ''))
    if problem:
        print(NO_SCREEN % problem, file=sys.stderr)
        return 1
    os.execvp('rosrun', ['rosrun', 'rviz', 'rviz'] + argv[1:])
    return 1  # not reached: execvp replaces this process or raises
