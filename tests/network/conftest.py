"""Fixtures of the network tests: children that are always stopped, and their logs on failure."""
import pytest

from course_testing.network.rosnet import Processes


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


@pytest.fixture(scope='class')
def class_processes(tmp_path_factory):
    """Children shared by the tests of one class (stopped before the next class starts its own)."""
    started = Processes(tmp_path_factory.mktemp('class'))
    yield started
    started.stop_all()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A failed test shows the end of every child's output (the simulator's log says why)."""
    outcome = yield
    report = outcome.get_result()
    if report.failed and call.when == 'call':
        for name in ('processes', 'class_processes', 'module_processes'):
            started = item.funcargs.get(name)
            if started is not None:
                report.sections.append(('children (%s)' % name, started.logs()))
