#!/usr/bin/env python3
"""How soon the simulators stop on Ctrl-C: turtlesim_node and fake_tb3_node, each started with
rosrun on a master of the bench's own and, once the master lists it as a publisher, sent SIGINT
(as Ctrl-C in its terminal; every rostest, grading run and check stops them so). Measured from the
signal: when the node has left the ROS graph (what a grading run waits for before it goes on) and
when its process has ended, in --rounds rounds, each on a quiet machine and beside one busy
process that the bench starts and stops. Prints a Markdown table. Run it after `source tools/env.sh`:

    /usr/bin/python3 bench/stop_bench.py [--rounds 5]

Targets (docs/benchmarks.md, "The simulators' stop"), quiet and beside the busy process: at the
median the node leaves the graph within TARGET_GRAPH_SECONDS and its process ends within
TARGET_EXIT_SECONDS, and no stop needs the SIGKILL of stop_process_group's timeout. The times are
looked at every 2 ms (with the master's answer, a millisecond or two).
"""
import argparse
import os
import signal
import statistics
import subprocess
import sys
import threading
import time

import rosgraph

from course_checks.robot import left_the_graph
from course_common.processes import stop_process_group
from course_common.waiting import wait_until
from course_testing.processes import busy_core
from fake_tb3_bench import start_master

# Each simulator: its rosrun command, its node's name, a topic it registers once it runs.
SIMULATORS = {
    'turtlesim': (['rosrun', 'turtlesim', 'turtlesim_node'], '/turtlesim', '/turtle1/pose'),
    'fake_tb3': (['rosrun', 'fake_tb3', 'fake_tb3_node'], '/fake_tb3', '/scan'),
}
TARGET_GRAPH_SECONDS = 0.1
TARGET_EXIT_SECONDS = 0.5
STOP_TIMEOUT = 15.0   # as the grader's stop of a simulator: SIGKILL after it
CALLER = '/stop_bench'


def publishes(topic):
    """The master lists a publisher of `topic` (the node registered it)."""
    publishers = rosgraph.Master(CALLER).getSystemState()[0]
    return any(name == topic and nodes for name, nodes in publishers)


def one_stop(command, node, topic):
    """Start the simulator, wait until it has registered `topic`, Ctrl-C it: (s to leave the
    graph, s to end, killed: whether the timeout's SIGKILL ended it)."""
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               start_new_session=True)
    try:
        wait_until(lambda: publishes(topic), 60, '%s on %s' % (node, topic))
    except BaseException:
        stop_process_group(process, STOP_TIMEOUT)
        raise
    seen = {}

    def watch():   # every 2 ms, on a thread of its own: the main thread is in stop_process_group
        while 'ended' not in seen:
            if 'left' not in seen and left_the_graph({node}):
                seen['left'] = time.monotonic()
            if process.poll() is not None:
                seen['ended'] = time.monotonic()
                seen.setdefault('left', seen['ended'])
            time.sleep(0.002)

    watcher = threading.Thread(target=watch)
    signalled = time.monotonic()
    watcher.start()
    code = stop_process_group(process, STOP_TIMEOUT)
    watcher.join()
    return seen['left'] - signalled, seen['ended'] - signalled, code == -signal.SIGKILL


def median_and_range(values):
    return '%.2f s (%.2f - %.2f)' % (statistics.median(values), min(values), max(values))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--rounds', type=int, default=5)
    args = parser.parse_args()
    core = start_master()
    stops = {(name, machine): [] for name in SIMULATORS for machine in ('quiet', 'one busy process')}
    try:
        for _ in range(args.rounds):
            for machine in ('quiet', 'one busy process'):
                with busy_core(machine != 'quiet'):
                    for name, (command, node, topic) in SIMULATORS.items():
                        stops[name, machine].append(one_stop(command, node, topic))
    finally:
        stop_process_group(core, STOP_TIMEOUT)
    print('| simulator | machine | leaves the graph | process ended | killed | met |')
    print('| --- | --- | --: | --: | --: | --- |')
    met_all = True
    for (name, machine), rows in stops.items():
        graph, ended, killed = zip(*rows)
        met = (sum(killed) == 0 and statistics.median(graph) <= TARGET_GRAPH_SECONDS
               and statistics.median(ended) <= TARGET_EXIT_SECONDS)
        met_all &= met
        print('| %s | %s | %s | %s | %d of %d | %s |' % (
            name, machine, median_and_range(graph), median_and_range(ended), sum(killed), len(rows),
            'yes' if met else 'NO'))
    print('\nmedian (fastest - slowest) of %d rounds; targets: the graph left within %.1f s and the '
          'process ended within %.1f s at the median, no stop killed; load average %.1f'
          % (args.rounds, TARGET_GRAPH_SECONDS, TARGET_EXIT_SECONDS, os.getloadavg()[0]))
    return 0 if met_all else 1


if __name__ == '__main__':
    sys.exit(main())
