#!/usr/bin/env python3
"""Starting and stopping turtlesim: silent headless start, clean Ctrl-C, the canvas saved at shutdown
by the demo launch file, the window under Xvfb, and multisim.launch."""
import os
import signal
import subprocess
import tempfile
import unittest

import rospy
import rostest
from PIL import Image as PilImage

from course_common.topic_recorder import TopicRecorder
from course_testing.screen import VirtualScreen
from course_common.waiting import wait_until
from turtlesim.msg import Pose
from turtlesim.srv import SetPen, TeleportAbsolute
from turtlesim_testing import graph, published_topics

BACKGROUND = (69, 86, 255)
PEN = (179, 184, 255)
MAGENTA = (255, 0, 255)


def interrupt(process, timeout=30.0):
    """Ctrl-C as a shell would send it (to the whole process group); returns (exit code, stdout, stderr)."""
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGINT)
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        out, err = process.communicate()
        raise AssertionError('still running %.0f s after Ctrl-C:\n%s\n%s' % (timeout, out, err))
    return process.returncode, out, err


def registered(node):
    """Whether `rosnode list` shows the node: it still has a topic or service at the master."""
    return any(node in nodes for names in graph() for nodes in names.values())


def screenshot(screen, path, window='root'):
    """The screen (or one window) as an RGB picture."""
    with PilImage.open(screen.screenshot(path, window)) as image:
        return image.convert('RGB')


def count(image, colour):
    return sum(1 for pixel in image.getdata() if pixel == colour)


class LifecycleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('lifecycle_test')

    def start(self, argv, **env_changes):
        """Start a program (env_changes: variables to set, None to unset), in its own process group.

        It is interrupted at the end of the test even if the test fails.
        """
        env = dict(os.environ)
        for key, value in env_changes.items():
            if value is None:
                env.pop(key, None)
            else:
                env[key] = value
        process = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                                   start_new_session=True)
        self.addCleanup(lambda: process.returncode is None and interrupt(process))
        return process

    def test_headless_start_is_silent_and_ctrl_c_unregisters(self):
        sim = self.start(['rosrun', 'turtlesim', 'turtlesim_node', '__ns:=quiet'], DISPLAY=None)
        wait_until(lambda: '/quiet/turtle1/pose' in published_topics(), 20.0, '/quiet/turtle1/pose')
        code, out, err = interrupt(sim)
        self.assertEqual(err, '')
        self.assertIn('Starting turtlesim with node name /quiet/turtlesim', out)
        self.assertIn('Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]', out)
        self.assertEqual(code, 0, out)
        self.assertFalse(registered('/quiet/turtlesim'))
        self.assertNotIn('/quiet/turtle1/pose', published_topics())
        self.assertNotIn('/quiet/spawn', graph()[2])

    def test_demo_launch_saves_the_square_at_shutdown(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, 'square.png')
            demo = self.start(['roslaunch', 'turtlesim', 'draw_square_demo.launch', 'canvas_png:=' + path])
            wait_until(lambda: '/turtle1/pose' in published_topics(), 30.0, '/turtle1/pose')
            poses = TopicRecorder('/turtle1/pose', Pose)
            wait_until(lambda: (poses.latest() or Pose()).x > 6.8, 20.0, 'turtle1 to drive 1.3 m to the right')
            poses.close()
            code, out, err = interrupt(demo)
            self.assertIn('saved the canvas to %s' % path, out)
            with PilImage.open(path) as png:
                picture = png.convert('RGB')
            self.assertEqual(picture.getpixel((480, 20)), BACKGROUND)
            # the first side of the square: the default pen along y = 5.544445 (row 249.5) from x = 255 px on,
            # short of the turtle icon (x >= 6.8 m, 306 px, minus 16 px to its tail)
            self.assertEqual([picture.getpixel((col, 249)) for col in range(262, 287, 5)], [PEN] * 5)
            self.assertFalse(registered('/turtlesim'))

    def test_window_under_xvfb_shows_the_trail(self):
        screen = self.enterContext(VirtualScreen(640, 560))
        with tempfile.TemporaryDirectory() as folder:
            shot = os.path.join(folder, 'screen.png')
            sim = self.start(['rosrun', 'turtlesim', 'turtlesim_node', '__ns:=windowed'], DISPLAY=screen.display)
            rospy.wait_for_service('/windowed/turtle1/teleport_absolute', 20.0)
            rospy.ServiceProxy('/windowed/turtle1/set_pen', SetPen)(*MAGENTA, 5, 0)
            rospy.ServiceProxy('/windowed/turtle1/teleport_absolute', TeleportAbsolute)(2.0, 2.0, 1.0)
            # the trail from the centre to (2, 2) m is about 226 px long and 5 px wide
            wait_until(lambda: count(screenshot(screen, shot), MAGENTA) > 800, 20.0,
                       'the magenta trail on the screen')
            window = screenshot(screen, shot, screen.window_id('TurtleSim'))
            self.assertEqual(window.size, (500, 500))
            self.assertEqual(window.getpixel((480, 20)), BACKGROUND)
            code, _, err = interrupt(sim)
            self.assertEqual((code, err), (0, ''))
            wait_until(lambda: screen.window_id('TurtleSim') is None, 10.0, 'the window to close')

            quiet = self.start(['rosrun', 'turtlesim', 'turtlesim_node', '__ns:=no_gui', '_gui:=false'],
                          DISPLAY=screen.display)
            # half a second of poses: the time a window would need to appear (it takes ~50 ms)
            poses = TopicRecorder('/no_gui/turtle1/pose', Pose)
            wait_until(lambda: poses.count() > 30, 20.0, 'poses from /no_gui/turtlesim')
            poses.close()
            self.assertIsNone(screen.window_id('TurtleSim'))
            self.assertEqual(interrupt(quiet)[2], '')

    def test_multisim_runs_two_independent_simulators(self):
        multisim = self.start(['roslaunch', 'turtlesim', 'multisim.launch'])
        wait_until(lambda: {'/turtlesim1/turtle1/pose', '/turtlesim2/turtle1/pose'} <= set(published_topics())
                   and {'/turtlesim1/spawn', '/turtlesim2/reset'} <= set(graph()[2]), 30.0, 'both simulators')
        self.assertTrue(registered('/turtlesim1/sim') and registered('/turtlesim2/sim'))
        services = graph()[2]
        self.assertEqual(services['/turtlesim1/spawn'], ['/turtlesim1/sim'])
        self.assertEqual(services['/turtlesim2/reset'], ['/turtlesim2/sim'])
        rospy.ServiceProxy('/turtlesim1/turtle1/teleport_absolute', TeleportAbsolute)(1.0, 1.0, 0.0)
        first = TopicRecorder('/turtlesim1/turtle1/pose', Pose).next_message()
        second = TopicRecorder('/turtlesim2/turtle1/pose', Pose).next_message()
        self.assertAlmostEqual(first.x, 1.0, places=5)
        self.assertAlmostEqual(second.x, 5.544445, places=5)
        interrupt(multisim)
        self.assertFalse(registered('/turtlesim1/sim') or registered('/turtlesim2/sim'))


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'lifecycle', LifecycleTest)
