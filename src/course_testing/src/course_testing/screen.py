"""A virtual X screen (Xvfb) for windows that tests and the tour look at, and screenshots of it."""
import os
import re
import shutil
import subprocess

import numpy
from PIL import Image


def red_pixels(path):
    """How many pixels of a PNG are pure-ish red: rviz's laser points, fake_tb3's scan."""
    with Image.open(path) as image:
        rgb = numpy.asarray(image.convert('RGB')).astype(int)
    return int(numpy.sum((rgb[:, :, 0] > 200) & (rgb[:, :, 1] < 60) & (rgb[:, :, 2] < 60)))


def uncovered_pixels(path):
    """The pixels of a screenshot that no window covers (Xvfb's root window is pure black): how
    many, and their bounding box (left, top, right, bottom), None when there are none."""
    with Image.open(path) as image:
        rgb = numpy.asarray(image.convert('RGB'))
    black = numpy.all(rgb == 0, axis=2)
    rows, columns = numpy.nonzero(black)
    if not len(rows):
        return 0, None
    return int(black.sum()), (int(columns.min()), int(rows.min()), int(columns.max()), int(rows.max()))


def can_make_screens():
    """True when Xvfb and ImageMagick's `import` are installed (tools/debian-packages.txt lists them)."""
    return bool(shutil.which('Xvfb') and shutil.which('import'))


class VirtualScreen:
    """Context manager: an Xvfb on a display number it picks free (-displayfd), stopped at exit."""

    def __init__(self, width=1280, height=1024):
        self.width, self.height = width, height
        self.size = '%dx%dx24' % (width, height)
        self.display = None
        self._xvfb = None

    def __enter__(self):
        read_end, write_end = os.pipe()
        self._xvfb = subprocess.Popen(
            ['Xvfb', '-displayfd', str(write_end), '-screen', '0', self.size, '-nolisten', 'tcp'],
            pass_fds=(write_end,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(write_end)
        with os.fdopen(read_end) as announced:
            number = announced.readline().strip()
        if not number:
            self._xvfb.wait(10)
            raise RuntimeError('Xvfb did not start (exit status %s)' % self._xvfb.returncode)
        self.display = ':' + number
        return self

    def __exit__(self, *exc):
        self._xvfb.terminate()
        self._xvfb.wait(10)
        return False

    def environment(self, base=None):
        """A copy of the environment (default os.environ) whose programs draw on this screen."""
        return dict(os.environ if base is None else base, DISPLAY=self.display)

    def screenshot(self, path, window='root'):
        """Write the whole screen (or one window, by id) as PNG to path and return path."""
        subprocess.run(['import', '-display', self.display, '-window', window, path], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30)
        return path

    def window_id(self, title):
        """The id of the window with this title, or None while there is none.

        Asked of xwininfo, because `import -window <title>` waits for ever for a missing window.
        """
        result = subprocess.run(['xwininfo', '-display', self.display, '-name', title],
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                universal_newlines=True, timeout=30)
        match = re.search(r'Window id: (0x[0-9a-f]+)', result.stdout)
        return match.group(1) if result.returncode == 0 and match else None
