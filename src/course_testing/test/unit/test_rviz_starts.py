"""course_testing.rviz: rviz started until it draws, through a real roslaunch whose rviz is a stand-in
(test/fake_rviz) that is killed by a signal, exits, or draws, as its plan says. (What the tour's
lab does with two crashes in a row is tested with stand-in launches, in course_tour's units.)"""
import os
import re

import pytest

from course_common.processes import free_port
from course_common.waiting import wait_until
from course_testing.network.rosnet import Processes, start_master
from course_testing.processes import LoggedLaunch
from course_testing.rviz import killed_by, rviz_until_drawn
from course_testing.screen import VirtualScreen, red_pixels

LAUNCH = os.path.join(os.path.dirname(__file__), '..', 'fake_rviz', 'fake_rviz.launch')
DIED = ('[rviz-2] process has died [pid 11715, exit code %d, cmd /ws/devel/lib/fake_tb3/rviz_on_screen '
        '-d turtlebot3_gazebo_model.rviz __name:=rviz].\nInitiating shutdown!\n')


def test_the_signal_that_killed_a_node_is_named():
    assert killed_by('started\n' + DIED % -11, 'rviz') == 'SIGSEGV'
    assert killed_by(DIED % -6, 'rviz') == 'SIGABRT'


def test_a_node_that_exited_by_itself_or_still_runs_was_killed_by_nothing():
    assert killed_by(DIED % 1, 'rviz') is None
    assert killed_by('process[rviz-2]: started with pid [11715]\n', 'rviz') is None


def test_another_node_killed_by_a_signal_is_not_rviz_killed():
    other = ('[robot_state_publisher-1] process has died [pid 11714, exit code -9, cmd '
             '/usr/lib/robot_state_publisher/robot_state_publisher __name:=robot_state_publisher].\n')
    assert killed_by(other, 'rviz') is None
    assert killed_by(DIED.replace('__name:=rviz', '__name:=rviz_2') % -11, 'rviz') is None
    assert killed_by(other + DIED % -11, 'rviz') == 'SIGSEGV'


@pytest.fixture(scope='module')
def master(tmp_path_factory):
    """A master of the tests' own, answering before the first roslaunch (which would otherwise
    start one of its own on the same port)."""
    port = free_port()
    uri = 'http://localhost:%d' % port
    processes = Processes(tmp_path_factory.mktemp('master'))
    try:
        start_master(processes, dict(os.environ, ROS_MASTER_URI=uri), port)
        yield uri
    finally:
        processes.stop_all()


class Starts:
    """Starts the stand-in's launch on `screen`, each start's output in its own file; keeps them all."""

    def __init__(self, tmp_path, master, screen, plan):
        self.tmp_path, self.master, self.screen = tmp_path, master, screen
        self.plan = tmp_path / 'plan'
        self.plan.write_text('\n'.join(plan))
        self.launches = []

    def __call__(self):
        env = self.screen.environment(dict(os.environ, ROS_MASTER_URI=self.master))
        self.launches.append(LoggedLaunch(['roslaunch', LAUNCH, 'plan:=%s' % self.plan],
                                          str(self.tmp_path / ('launch-%d.log' % len(self.launches))), env))
        return self.launches[-1]


def until_drawn(tmp_path, master, plan, timeout=60.0):
    with VirtualScreen(640, 480) as screen:
        starts = Starts(tmp_path, master, screen, plan)
        screenshot = str(tmp_path / 'screen.png')
        try:
            launch, notes = rviz_until_drawn(starts, LoggedLaunch.stop, screen, screenshot,
                                             red_at_least=5000, timeout=timeout)
        except AssertionError as failure:
            return starts.launches, None, str(failure)
        red = red_pixels(screenshot)
        launch.stop()
        return starts.launches, notes, red


def test_rviz_killed_by_a_signal_is_started_once_more_and_that_is_said(tmp_path, master):
    launches, notes, red = until_drawn(tmp_path, master, ['segv', 'draw'])
    assert len(launches) == 2 and red >= 640 * 480 * 0.9
    assert notes == ['rviz was killed by SIGSEGV at its first start, before it drew: started again']
    assert all(launch.exited() for launch in launches)  # the one that drew was stopped


def test_rviz_that_exits_by_itself_is_not_started_again(tmp_path, master):
    launches, notes, failure = until_drawn(tmp_path, master, ['exit', 'draw'])
    assert len(launches) == 1
    assert failure.startswith('rviz ended before it drew (first start, not by a signal)')
    assert 'exit code 3' in failure


def test_rviz_that_never_draws_fails_at_the_timeout_and_is_stopped(tmp_path, master):
    launches, notes, failure = until_drawn(tmp_path, master, ['blank', 'draw'], timeout=4.0)
    assert len(launches) == 1
    # What roslaunch printed follows (under load it may not have printed anything in 4 s).
    assert failure.startswith('timed out after 4.0 s waiting for rviz to draw the laser points and fill the '
                              'screen (first start); the last screenshot: 0 laser-red pixels, ')
    assert '; its launch said:\n' in failure
    wait_until(launches[0].exited, 5, 'the launch to be stopped')


def test_rviz_whose_window_leaves_part_of_the_screen_black_has_not_drawn(tmp_path, master):
    launches, notes, failure = until_drawn(tmp_path, master, ['small', 'draw'], timeout=10.0)
    assert len(launches) == 1
    # The red 400 x 300 window at the top left, the rest of the 640 x 480 screen black.
    assert re.search(r'the last screenshot: 1\d{5} laser-red pixels, 1\d{5} uncovered \(black\) from \(0, 0\) '
                     r'to \(639, 479\)', failure), failure
    wait_until(launches[0].exited, 5, 'the launch to be stopped')


class Silent:
    """A launch that runs and prints, and never draws."""
    stopped = False

    def exited(self):
        return False

    def output(self):
        return 'process[rviz-1]: started with pid [4242]\n'


def test_the_timeout_quotes_what_the_launch_printed(tmp_path):
    with VirtualScreen(64, 48) as screen:
        launch = Silent()
        with pytest.raises(AssertionError) as failure:
            rviz_until_drawn(lambda: launch, lambda stopped: setattr(stopped, 'stopped', True), screen,
                             str(tmp_path / 'screen.png'), red_at_least=10, timeout=1.0)
    assert str(failure.value) == ('timed out after 1.0 s waiting for rviz to draw the laser points and fill the '
                                  'screen (first start); the last screenshot: 0 laser-red pixels, 3072 uncovered '
                                  '(black) from (0, 0) to (63, 47); its launch said:\n'
                                  'process[rviz-1]: started with pid [4242]\n')
    assert launch.stopped
