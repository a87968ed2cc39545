"""The grader starts fake_tb3 itself (its executable's main, prepared ahead of the run), not through
world.launch: the parameters it sets beside a run's own must be those world.launch would set, or
the run sees another simulator."""
import errno
import os
import re
import signal
import stat
import subprocess
import sys
import types
import xml.etree.ElementTree as ElementTree

import pytest
import rospkg
import yaml

from course_common.process_table import user_processes
from course_common.waiting import wait_until
from course_grader.labs import move_turtlebot3
from course_grader.labs.move_turtlebot3 import LAUNCH_DEFAULTS, PREPARED_FAKE_TB3, PreparedSimulator, Simulators


def world_launch_parameters():
    """{name: value} of the parameters world.launch gives the fake_tb3 node, its args at their defaults."""
    root = ElementTree.parse(os.path.join(rospkg.RosPack().get_path('fake_tb3'), 'launch', 'world.launch')).getroot()
    defaults = {arg.get('name'): arg.get('default') for arg in root.iter('arg')}
    node = root.find('node')
    parameters = {}
    for param in node.findall('param'):
        text = re.sub(r'\$\(arg (\w+)\)', lambda match: defaults[match.group(1)], param.get('value'))
        parameters[param.get('name')] = text if param.get('type') == 'str' else yaml.safe_load(text)
    for rosparam in node.findall('rosparam'):
        parameters[rosparam.get('param')] = yaml.safe_load(rosparam.text)
    return parameters


def test_the_grader_sets_what_world_launch_sets_beside_a_runs_settings():
    launched = world_launch_parameters()
    assert {name: launched[name] for name in LAUNCH_DEFAULTS} == LAUNCH_DEFAULTS


class SandboxOutOfProcesses:
    """A session whose trusted side cannot start a program while `full` holds (a fork bomb of the
    run before took every process or thread of the sandbox)."""

    def __init__(self, folder):
        self.folder = folder
        self.full = True
        self.started = []

    def log_path(self, name):
        return os.path.join(self.folder, name)

    def record_path(self, name):
        return os.path.join(self.folder, '%s.record' % name)

    def trusted(self, argv, log_name, record=None):
        if self.full:
            raise OSError(errno.EAGAIN, 'no thread left to read the output of python3')
        self.started.append((log_name, record))
        return types.SimpleNamespace(ended=lambda: False)


def test_a_simulator_that_could_not_start_leaves_nothing_in_the_way_of_the_next(tmp_path):
    session = SandboxOutOfProcesses(str(tmp_path))
    simulators = Simulators(session, ['trajectory.py', 'laser_data.py'])
    with pytest.raises(OSError):
        simulators.take()
    assert os.listdir(str(tmp_path)) == []   # its FIFO gone
    session.full = False                      # the fork bomb stopped with its run
    assert simulators.take().log_name == 'sim_trajectory.txt'
    assert simulators.take().log_name == 'sim_laser_data.txt'
    assert [log for log, _ in session.started] == ['sim_trajectory.txt', 'sim_laser_data.txt']


def test_a_fifo_left_by_an_earlier_preparation_is_replaced(tmp_path):
    session = SandboxOutOfProcesses(str(tmp_path))
    session.full = False
    os.mkfifo(session.log_path('.sim_laser_data.txt.go'))
    prepared = PreparedSimulator(session, 'sim_laser_data.txt')
    assert stat.S_ISFIFO(os.stat(prepared.fifo).st_mode)


def test_during_the_build_only_the_first_runs_simulator_starts_the_others_once_that_run_is_under_way(tmp_path):
    # Three importing beside the build took the processor from the first one's start (0.3 - 0.8 s
    # more before the first run); the first run's watch leaves it mostly idle.
    session = SandboxOutOfProcesses(str(tmp_path))
    session.full, session.only = False, None
    move_turtlebot3.prepare(session)
    assert [log for log, _ in session.started] == ['sim_trajectory.txt']
    first = types.SimpleNamespace(simulators=session.simulators)
    assert session.simulators.take().log_name == 'sim_trajectory.txt'
    session.full = True   # the first run's node took every process: the others start with their runs
    move_turtlebot3.Run.under_way(first)
    session.full = False
    move_turtlebot3.Run.under_way(first)
    assert [log for log, _ in session.started] == ['sim_trajectory.txt', 'sim_laser_data.txt', 'sim_avoid_obstacle.txt']
    assert [session.simulators.take().log_name for _ in range(2)] == ['sim_laser_data.txt', 'sim_avoid_obstacle.txt']


class RealStart(SandboxOutOfProcesses):
    """A session whose trusted side runs the program it is given, with a fake_tb3 whose main()
    writes the settings it was started with to `told`."""

    def __init__(self, folder):
        super().__init__(folder)
        self.full = False
        stub = os.path.join(folder, 'stub', 'fake_tb3')
        os.makedirs(stub)
        open(os.path.join(stub, '__init__.py'), 'w').close()
        self.told = os.path.join(folder, 'told.json')
        with open(os.path.join(stub, 'node.py'), 'w') as node:
            node.write('def main(settings):\n    open(%r, "w").write(settings)\n' % self.told)
        self.argv = None

    def trusted(self, argv, log_name, record=None):
        self.argv = argv
        process = subprocess.Popen(argv, env=dict(os.environ, PYTHONPATH=os.path.join(self.folder, 'stub')))
        self.started.append(process)
        return types.SimpleNamespace(ended=lambda: process.poll() is not None)


def test_the_graders_settings_reach_fake_tb3_through_its_fifo_alone(tmp_path, request):
    # The put-back's moment and distance (fake_tb3.put_back): on the master's parameters or the
    # command line (/proc/PID/cmdline) any node could read them.
    session = RealStart(str(tmp_path))
    prepared = PreparedSimulator(session, 'sim_avoid_obstacle.txt')
    request.addfinalizer(lambda: [(process.kill(), process.wait()) for process in session.started])
    assert stat.S_IMODE(os.stat(prepared.fifo).st_mode) == 0o600
    settings = '{"put_back": {"min_drive": 0.5, "after": 7.25, "distance": 0.8125}}'
    prepared.start(20, settings)
    assert session.started[0].wait(20) == 0
    with open(session.told) as told:
        assert told.read() == settings
    assert not any('put_back' in arg for arg in session.argv)
    assert not os.path.exists(prepared.fifo)


def test_a_prepared_simulator_ends_when_its_session_is_killed(tmp_path, request):
    # A session killed with SIGKILL stops nothing it started: its prepared fake_tb3, waiting on a
    # FIFO that no one would open any more, waited for ever (2026-12-04).
    stub = tmp_path / 'stub' / 'fake_tb3'
    stub.mkdir(parents=True)
    (stub / '__init__.py').write_text('')
    imported, ran = tmp_path / 'imported', tmp_path / 'ran'
    (stub / 'node.py').write_text('open(%r, "w").close()\n\n\ndef main(settings):\n    open(%r, "w").close()\n'
                                  % (str(imported), str(ran)))
    fifo = str(tmp_path / 'go')
    os.mkfifo(fifo, 0o600)
    session = subprocess.Popen(
        [sys.executable, '-c', 'import subprocess, sys, time\n'
         'print(subprocess.Popen(sys.argv[1:]).pid, flush=True)\ntime.sleep(120)\n',
         sys.executable, '-c', PREPARED_FAKE_TB3, fifo, '__name:=fake_tb3'],
        stdout=subprocess.PIPE, universal_newlines=True, env=dict(os.environ, PYTHONPATH=str(tmp_path / 'stub')))
    request.addfinalizer(lambda: (session.kill(), session.wait()))
    simulator = int(session.stdout.readline())
    # Alive, not a zombie (one that ended waits for its new parent to reap it).
    running = lambda: simulator in user_processes(os.getuid())
    request.addfinalizer(lambda: running() and os.kill(simulator, signal.SIGKILL))
    # While its session lives, it waits on the FIFO (its modules imported).
    wait_until(imported.exists, 20, 'the prepared simulator to import fake_tb3')
    assert running()
    session.kill()
    session.wait()
    wait_until(lambda: not running(), 5, 'the prepared simulator to end with its session')
    assert not ran.exists()   # it never ran
