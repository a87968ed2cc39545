"""Floods and bad input against turtlesim and fake_tb3: each keeps its rates (turtlesim's pose at
every tick, fake_tb3's odom at 30 Hz and scan at 5 Hz), never publishes a NaN, and nothing crashes.
One master and one simulator for all the tests of a simulator, as a long session would have."""
import pytest

from course_testing.network import scenarios
from course_testing.network.scenarios import FLOOD_RATE, RATE_TOLERANCE


def pytest_generate_tests(metafunc):
    if 'bad_input' in metafunc.fixturenames:
        cases = metafunc.cls.bad_inputs
        metafunc.parametrize('bad_input', cases, ids=[label for label, _ in cases])


def assert_rates_hold(graph, rates):
    for topic, (_, expected) in graph.probes.items():
        assert rates[topic] == pytest.approx(expected, rel=RATE_TOLERANCE), (topic, rates)
        assert rates[topic + ' max gap'] < max(0.1, 2.5 / expected), (topic, rates)


class SimulatorAbuse:
    """The tests, for the simulator a subclass names (start: a scenarios.start_* function)."""
    start = None
    bad_inputs = []

    @pytest.fixture(scope='class')
    def graph(self, class_processes):
        return type(self).start(class_processes)

    def test_flood_of_10000_commands_a_second_keeps_the_rates(self, graph):
        result = scenarios.flood(graph, FLOOD_RATE, seconds=3.0, twists='0.2,0,1')
        assert result['published_hz'] >= 0.95 * FLOOD_RATE, result
        assert result['received_hz'] >= 0.95 * FLOOD_RATE, result   # the simulator really read them
        assert_rates_hold(graph, result)
        graph.main_probe.wait_for(lambda values: abs(values[graph.speed_field] - 0.2) < 1e-6, 2,
                                  'the flooded command to be obeyed')

    def test_bad_input_is_refused_and_the_simulator_lives_on(self, graph, bad_input):
        _label, case = bad_input
        assert case(graph)  # each case asserts what it checks; it returns its line for the table

    def test_after_everything_no_nan_was_published_and_the_rates_hold(self, graph):
        assert graph.nan_messages() == 0
        assert_rates_hold(graph, scenarios.quiet_rates(graph))
        assert graph.simulator.running()


class TestTurtlesim(SimulatorAbuse):
    start = staticmethod(scenarios.start_turtlesim)
    bad_inputs = scenarios.TURTLESIM_BAD_INPUTS


class TestFakeTb3(SimulatorAbuse):
    start = staticmethod(scenarios.start_fake_tb3)
    bad_inputs = scenarios.FAKE_TB3_BAD_INPUTS
