"""Fixtures of the network tests: children that are always stopped, the loopback library."""
import os

import pytest

from rosnet import Processes, project_environment


@pytest.fixture
def processes(tmp_path):
    started = Processes(tmp_path)
    yield started
    started.stop_all()


@pytest.fixture(scope='module')
def module_processes(tmp_path_factory):
    """Children shared by the tests of one module (one master and simulator for all of them)."""
    started = Processes(tmp_path_factory.mktemp('module'))
    yield started
    started.stop_all()


@pytest.fixture(scope='session')
def loopback_library():
    """libros_loopback.so as built into the workspace (devel or install space)."""
    for folder in project_environment().get('LD_LIBRARY_PATH', '').split(':'):
        candidate = os.path.join(folder, 'libros_loopback.so')
        if folder and os.path.isfile(candidate):
            return candidate
    raise AssertionError('libros_loopback.so is not in the workspace: build ros_loopback first')
