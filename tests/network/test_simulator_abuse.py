"""Floods and bad input against turtlesim and fake_tb3: each keeps its rates (turtlesim's pose at
62.5 Hz, fake_tb3's odom at 30 Hz and scan at 5 Hz), never publishes a NaN, and nothing crashes.
One master and one simulator for all the tests of a simulator, as a long session would have."""
import pytest

import scenarios
from rosnet import Processes, now
from scenarios import FLOOD_RATE, RATE_TOLERANCE

COMMON_BAD_INPUTS = [('non-finite cmd_vel', scenarios.non_finite_commands),
                     ('String on cmd_vel', scenarios.wrong_type_on_cmd_vel),
                     ('TCPROS junk', scenarios.garbage_on_topic_port),
                     ('XML-RPC junk', scenarios.garbage_xmlrpc)]
BAD_INPUTS = {
    'turtlesim': COMMON_BAD_INPUTS + [
        ('raw /spawn junk', lambda graph: scenarios.garbage_service_calls(graph, '/spawn')),
        ('rosservice wrong fields', scenarios.wrong_service_fields),
        ('odd spawn/kill names', scenarios.odd_turtle_names)],
    'fake_tb3': COMMON_BAD_INPUTS + [
        ('raw save_picture junk', lambda graph: scenarios.garbage_service_calls(graph, '/fake_tb3/save_picture'))],
}
STARTERS = {'turtlesim': scenarios.start_turtlesim, 'fake_tb3': scenarios.start_fake_tb3}


def pytest_generate_tests(metafunc):
    if 'bad_input' in metafunc.fixturenames:
        pairs = [(simulator, case) for simulator, cases in BAD_INPUTS.items() for case in cases]
        metafunc.parametrize(('graph', 'bad_input'), pairs, indirect=['graph'], scope='module',
                             ids=['%s: %s' % (simulator, label) for simulator, (label, _) in pairs])
    elif 'graph' in metafunc.fixturenames:
        metafunc.parametrize('graph', list(BAD_INPUTS), indirect=True, scope='module')


@pytest.fixture(scope='module')
def graph(request, tmp_path_factory):
    processes = Processes(tmp_path_factory.mktemp(request.param))
    try:
        yield STARTERS[request.param](processes)
    finally:
        processes.stop_all()


def assert_rates_hold(graph, rates):
    for topic, (_, expected) in graph.probes.items():
        assert rates[topic] == pytest.approx(expected, rel=RATE_TOLERANCE), (topic, rates)
        assert rates[topic + ' max gap'] < max(0.1, 2.5 / expected), (topic, rates)


def test_flood_of_10000_commands_a_second_keeps_the_rates(graph):
    result = scenarios.flood(graph, FLOOD_RATE, seconds=3.0, twists='0.2,0,1')
    assert result['published_hz'] >= 0.95 * FLOOD_RATE, result
    assert result['received_hz'] >= 0.95 * FLOOD_RATE, result   # the simulator really read them
    assert_rates_hold(graph, result)
    assert graph.main_probe.wait_for(lambda values: abs(values[graph.speed_field] - 0.2) < 1e-6, 2,
                                     'the flooded command to be obeyed')


def test_bad_input_is_refused_and_the_simulator_lives_on(graph, bad_input):
    label, case = bad_input
    assert case(graph)


def test_after_everything_no_nan_was_published_and_the_rates_hold(graph):
    assert graph.nan_messages() == 0
    start = now()
    slowest, slowest_rate = min(graph.probes.values(), key=lambda probe_rate: probe_rate[1])
    slowest.wait_for_messages(int(1.5 * slowest_rate) + 1, timeout=5)
    end = now()
    assert_rates_hold(graph, {key: value for topic, (probe, _) in graph.probes.items()
                              for key, value in ((topic, probe.rate(start, end)),
                                                 (topic + ' max gap', probe.max_gap(start, end)))})
    assert graph.simulator.running()
