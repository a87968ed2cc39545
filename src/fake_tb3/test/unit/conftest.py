"""Shared by the unit tests: a log object for the simulation that keeps its lines."""
import pytest


class RecordingLog:
    """Has the info() and warning() a Simulation logs to; keeps (level, text) lines."""

    def __init__(self):
        self.lines = []

    def info(self, text):
        self.lines.append(('info', text))

    def warning(self, text):
        self.lines.append(('warning', text))


@pytest.fixture
def recording_log():
    return RecordingLog()
