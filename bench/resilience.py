#!/usr/bin/env python3
"""Resilience of the workspace, measured and printed as Markdown tables.

    source tools/env.sh && /usr/bin/python3 bench/resilience.py [--no-two-hosts]

What listens where, load held (10 000 cmd_vel a second: the rate reached, the rates kept), bad inputs
tried, faults survived, the link between two hosts cut and restored (root only), NaN published, and
a summary. Runs the scenarios of course_testing.network, as tests/network/ does (about two minutes);
a scenario that fails shows as FAILED in its row instead of a number.
"""
import argparse
import os
import sys
import tempfile
import traceback

from course_testing.network import faults, netns, scenarios
from course_testing.network.rosnet import Processes, is_loopback


def table(title, header, rows):
    print('\n### %s\n' % title)
    print('| ' + ' | '.join(header) + ' |')
    print('|' + '---|' * len(header))
    for row in rows:
        print('| ' + ' | '.join(str(cell).replace('\n', ' ') for cell in row) + ' |')
    sys.stdout.flush()


class Summary:
    """Counts what held and what did not, for the last table."""

    def __init__(self):
        self.counts = {}  # kind -> [held, tried]
        self.nan_messages = 0
        self.notes = {}

    def attempt(self, kind, function, *args):
        """function(*args), counted under `kind`; on failure the sentence saying why."""
        held_tried = self.counts.setdefault(kind, [0, 0])
        held_tried[1] += 1
        try:
            result = function(*args)
        except AssertionError as error:
            return 'FAILED: %s' % str(error).strip().splitlines()[0][:160]
        except Exception:  # a broken scenario: the other rows still run
            return 'ERROR: %s' % traceback.format_exc().strip().splitlines()[-1][:160]
        held_tried[0] += 1
        return result


def with_processes(function, *args):
    """function(processes, *args), its children stopped afterwards whatever happens."""
    processes = Processes(tempfile.mkdtemp(prefix='resilience-'))
    try:
        return function(processes, *args)
    finally:
        processes.stop_all()


def security(processes, summary):
    listening = scenarios.listening_ros_sockets(processes)
    rows = [(program, ', '.join('%s:%d' % socket for socket in sorted(sockets)),
             'yes' if all(is_loopback(address) for address, _ in sockets) else '**NO**')
            for program, sockets in listening]
    table('Security: listening TCP sockets, project environment',
          ('process', 'listens on', 'loopback only'), rows)
    summary.notes['processes listening on loopback only'] = '%d of %d' % (
        sum(row[2] == 'yes' for row in rows), len(rows))


def load_and_bad_inputs(processes, simulator, start, bad_inputs, summary):
    graph = start(processes)
    result = summary.attempt('load held', scenarios.flood, graph)
    if isinstance(result, str):
        rows = [('10 000 cmd_vel/s for 3 s', result)]
    else:
        rows = [('cmd_vel published (synchronous publisher)', '%.0f msg/s' % result['published_hz']),
                ('cmd_vel read by %s (its getBusStats)' % simulator, '%.0f msg/s' % result['received_hz'])]
        rows += [('%s meanwhile (nominal %g Hz)' % (topic, expected),
                  '%.2f Hz, longest gap %.0f ms' % (result[topic], 1000 * result[topic + ' max gap']))
                 for topic, (_, expected) in graph.probes.items()]
        kept = ', '.join('%s %.2f Hz' % (topic, result[topic]) for topic in graph.probes)
        summary.notes['load held: %s' % simulator] = '%.0f cmd_vel/s read; %s' % (result['received_hz'], kept)
    table('Load held: %s, 10 000 cmd_vel/s for 3 s' % simulator, ('measure', 'value'), rows)

    rows = [(label, summary.attempt('bad inputs refused', case, graph)) for label, case in bad_inputs]
    quiet = summary.attempt('rates kept afterwards', scenarios.quiet_rates, graph)
    rows.append(('afterwards, nothing going on', quiet if isinstance(quiet, str) else ', '.join(
        '%s %.2f Hz' % (topic, quiet[topic]) for topic in graph.probes)))
    rows.append(('%s still running' % simulator, 'yes' if graph.simulator.running() else '**NO**'))
    table('Bad inputs tried: %s' % simulator, ('input', 'what happened'), rows)
    summary.nan_messages += graph.nan_messages()


def seconds(result):
    return result if isinstance(result, str) else '; '.join('%s %.2f s' % item for item in result.items())


def fault_rows(processes, summary):
    graph = scenarios.start_turtlesim(processes)
    rows = [(label, seconds(summary.attempt('faults survived', scenario, graph))) for label, scenario in (
        ('turtlesim killed (SIGKILL) and restarted under circle', faults.simulator_killed_under_circle),
        ('circle killed and restarted', faults.course_node_killed),
        ('my_turtle_node killed and restarted, then turtlesim', faults.teleop_relay_killed))]
    summary.nan_messages += graph.nan_messages()
    return rows


def master_rows(processes, summary):
    graph = scenarios.start_turtlesim(processes)
    result = summary.attempt('faults survived', faults.master_restarted, graph)
    summary.nan_messages += graph.nan_messages()
    if isinstance(result, str):
        return [('master killed and started again', result)]
    return [('master killed: circle goes on driving turtlesim', 'yes (connections made before)'),
            ('new master on the same port knows of /turtle1/pose',
             'publishers %s, subscribers %s' % result['pose_registrations_on_new_master']),
            ('turtlesim, circle started again', 'publishers %s, subscribers %s; driving after %.2f s' % (
                result['pose_registrations_after_restarting_nodes']
                + (result['drives_after_restarting_nodes_s'],)))]


def two_host_rows(processes, across, summary):
    hosts = netns.TwoHosts()
    try:
        hosts.create()
        remote = across(processes, hosts)
        rows = []
        for how in ('down', 'loss'):
            result = summary.attempt('two-host link cuts survived', netns.cut_and_restore, hosts, remote, how)
            if not isinstance(result, str):
                stop, resume = result
                late = '' if stop <= remote.stop_within else ' **LATE**'
                result = ('stopped %.3f s after the cut (limit %.3f s)%s; driven again %.2f s after the link '
                          'came back' % (stop, remote.stop_within, late, resume))
            rows.append((across.__name__.replace('_across', ''), how, result))
        summary.nan_messages += remote.probe.nan_count()
        return rows
    finally:
        processes.stop_all()  # before the namespaces go
        hosts.delete()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--no-two-hosts', action='store_true',
                        help='leave out the network namespaces (they need root)')
    arguments = parser.parse_args()
    summary = Summary()
    print('# Resilience of the workspace')
    with_processes(security, summary)
    for simulator, start, bad_inputs in (
            ('turtlesim', scenarios.start_turtlesim, scenarios.TURTLESIM_BAD_INPUTS),
            ('fake_tb3', scenarios.start_fake_tb3, scenarios.FAKE_TB3_BAD_INPUTS)):
        with_processes(load_and_bad_inputs, simulator, start, bad_inputs, summary)
    table('Faults survived', ('fault', 'measured'),
          with_processes(fault_rows, summary) + with_processes(master_rows, summary))
    if arguments.no_two_hosts or os.geteuid() != 0:
        why = '--no-two-hosts' if arguments.no_two_hosts else 'network namespaces need root'
        print('\n(two hosts left out: %s)' % why)
    else:
        table('Two hosts: the link cut and restored', ('robot', 'cut', 'what happened'),
              [row for across in (netns.turtlesim_across, netns.fake_tb3_across)
               for row in with_processes(two_host_rows, across, summary)])
    rows = [(kind, '%d of %d' % tuple(counts)) for kind, counts in summary.counts.items()]
    rows += list(summary.notes.items())
    rows.append(('messages with a NaN (pose, odom, scan, all of the above)', summary.nan_messages))
    table('Summary', ('result', 'value'), rows)


if __name__ == '__main__':
    main()
