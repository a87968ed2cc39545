"""The rviz lab when rviz ends before it draws: the signal named, one more start for a crash, none
for an exit of its own. rviz, Xvfb and the screenshots are stand-ins; the lab's logic, and
course_testing.rviz's, are the real ones."""
import pytest

from course_testing import rviz
from course_tour import labs

DIED = ('[rviz-2] process has died [pid 11715, exit code %d, cmd /ws/devel/lib/fake_tb3/rviz_on_screen '
        '-d turtlebot3_gazebo_model.rviz __name:=rviz].\nInitiating shutdown!\n')


class FakeLaunch:
    def __init__(self, output):
        self._output = output

    def exited(self):
        return bool(self._output)

    def output(self):
        return self._output


class FakeSession:
    """Each rviz launch ends with the next of `rviz_outputs` ('' : it runs and draws)."""

    def __init__(self, rviz_outputs):
        self.rviz_outputs = list(rviz_outputs)
        self.rviz_starts = 0
        self.running = []
        self.env = {}

    def picture(self, name):
        return name

    def launch(self, package, launch_file, env=None):
        if launch_file == 'turtlebot3_gazebo_rviz.launch':
            self.rviz_starts += 1
            launched = FakeLaunch(self.rviz_outputs.pop(0))
        else:
            launched = FakeLaunch('')
        self.running.append(launched)
        return launched

    def stop(self, launched):
        self.running.remove(launched)


class FakeScreen:
    width, height = 1280, 1024

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def environment(self, base):
        return dict(base)

    def screenshot(self, path):
        return path


@pytest.fixture
def screen(monkeypatch):
    monkeypatch.setattr(labs, 'can_make_screens', lambda: True)
    monkeypatch.setattr(labs, 'VirtualScreen', FakeScreen)
    monkeypatch.setattr(labs, 'red_pixels', lambda path: 5000)
    monkeypatch.setattr(rviz, 'red_pixels', lambda path: 5000)
    monkeypatch.setattr(rviz, 'uncovered_pixels', lambda path: (0, None))   # rviz's window fills the screen


def test_rviz_that_draws_at_once_is_started_once(screen):
    session = FakeSession([''])
    report = labs.turtlebot3_rviz(session)
    assert session.rviz_starts == 1 and session.running == []
    assert report.lines == ['rviz drew the robot model and the scan: 5000 laser-red pixels']


def test_rviz_killed_by_a_signal_at_its_start_is_started_once_more_and_the_summary_says_so(screen):
    session = FakeSession([DIED % -11, ''])
    report = labs.turtlebot3_rviz(session)
    assert session.rviz_starts == 2 and session.running == []
    assert report.lines == ['rviz was killed by SIGSEGV at its first start, before it drew: started again',
                            'rviz drew the robot model and the scan: 5000 laser-red pixels']


def test_rviz_killed_at_both_starts_fails_the_lab_with_the_signal_and_the_launch_output(screen):
    session = FakeSession([DIED % -11, DIED % -11])
    with pytest.raises(AssertionError) as failure:
        labs.turtlebot3_rviz(session)
    assert str(failure.value).startswith('rviz ended before it drew (second start, SIGSEGV)')
    assert 'process has died [pid 11715, exit code -11' in str(failure.value)
    # Only the world's launch is left, for the session's stop_all (a lab that failed half way).
    assert session.rviz_starts == 2 and len(session.running) == 1


def test_rviz_that_exits_by_itself_is_not_started_again(screen):
    session = FakeSession([DIED % 1, ''])
    with pytest.raises(AssertionError) as failure:
        labs.turtlebot3_rviz(session)
    assert str(failure.value).startswith('rviz ended before it drew (first start, not by a signal)')
    assert session.rviz_starts == 1

