"""The TurtleSim window (Tk): shows the canvas with the turtles, refreshed while something changes.

Runs in the main thread (Tk wants that); the tick thread keeps stepping the world meanwhile.
Closing the window shuts the node down, like closing the original's window.
"""
import time
import tkinter

import rospy

from turtlesim import picture
from turtlesim.canvas import CANVAS_PX

REFRESH_MS = 40  # 25 pictures per second at most, and only when something changed


def run_window(node, running, poll_seconds):
    """Show the window while running() is true. Without a usable display, run headless."""
    try:
        root = tkinter.Tk()
    except tkinter.TclError as error:
        rospy.logwarn('Cannot open the TurtleSim window (%s): running without a window' % error)
        while running():
            time.sleep(poll_seconds)
        return
    root.title('TurtleSim')
    root.resizable(False, False)
    photo = tkinter.PhotoImage(width=CANVAS_PX, height=CANVAS_PX)
    tkinter.Label(root, image=photo, borderwidth=0, highlightthickness=0).pack()
    root.protocol('WM_DELETE_WINDOW', lambda: rospy.signal_shutdown('the TurtleSim window was closed'))
    shown = [None]  # revision of the world on screen

    def refresh():
        if not running():
            root.destroy()
            return
        revision = node.revision()
        if revision != shown[0]:
            photo.configure(data=picture.ppm_bytes(node.snapshot()), format='PPM')
            shown[0] = revision
        root.after(REFRESH_MS, refresh)

    refresh()
    root.mainloop()
