#!/usr/bin/env python3
"""Where a simulated second of fake_tb3 goes: one robot in turtlebot3_world (or --robots N on the
bench's grid in the empty world), every topic at its simulated rate with a subscriber on each (raw,
in this process: fake_tb3_bench.RawSubscriber), the simulator as fast as it can run, profiled
(cProfile, the simulation's thread) for a few wall seconds.

Prints the real-time factor reached, the simulator's CPU split between its simulation thread and
rospy's threads, a breakdown of the simulation thread's time per simulated second (physics, ray
cast, message building, serialisation, handing messages to rospy, TF, /clock, pacing), and the
top functions by own time. Run after `source tools/env.sh`:

    bench/fake_tb3_profile.py [--seconds 8] [--top 5] [--robots 1]
"""
import argparse
import os
import pstats
import subprocess
import sys
import tempfile
import time

import rospy
from geometry_msgs.msg import Twist

from course_common.processes import stop_process_group
from course_common.waiting import wait_until
from fake_tb3_bench import TopicCounter, grid_of_robots, start_master

# Run inside the simulator's process: the node under cProfile, then its CPU times to a file.
PROFILED_NODE = '''
import cProfile, sys, threading, time
import fake_tb3.node
profile = cProfile.Profile(time.thread_time) if sys.argv.pop(3) == 'cpu' else cProfile.Profile()
spin = fake_tb3.node.FakeTb3Node.spin

def profiled_spin(node):  # the loop only: start-up is no simulated second's cost
    profile.enable()
    try:
        spin(node)
    finally:
        profile.disable()

fake_tb3.node.FakeTb3Node.spin = profiled_spin
try:
    fake_tb3.node.main()
finally:
    profile.dump_stats(sys.argv[1])
    with open(sys.argv[2], 'w') as out:
        out.write('%f %f' % (time.thread_time(), time.process_time()))
'''


def _entries(stats, file_part, name):
    """pstats entries (key, value) whose file ends with file_part and function is name."""
    return [(key, value) for key, value in stats.stats.items()
            if key[0].endswith(file_part) and key[2] == name]


def _cumulative(stats, file_part, name, caller=None, first_only=False):
    """Cumulative seconds of a function (only its calls from `caller`, (file part, name), if given;
    first_only: only the function of that name defined first in the file)."""
    entries = sorted(_entries(stats, file_part, name), key=lambda entry: entry[0][1])
    total = 0.0
    for _, (_, _, _, cumulative, callers) in entries[:1] if first_only else entries:
        if caller is None:
            total += cumulative
            continue
        for caller_key, timing in callers.items():
            if caller_key[0].endswith(caller[0]) and caller_key[2] == caller[1]:
                total += timing[3]
    return total


def breakdown(stats):
    """(total, [(part, seconds)]) of the simulation thread's wall time; parts named 'of which'
    are inside the part above them. Reads the profile of today's node and of the one before its
    batched scans and writes (rospy's publish() and a writer thread per connection)."""
    node = 'fake_tb3/node.py'
    batched = 'course_common/batched_writes.py'
    physics = _cumulative(stats, 'fake_tb3/simulation.py', 'step')
    raycast = (_cumulative(stats, 'fake_tb3/simulation.py', 'scans')
               or _cumulative(stats, 'fake_tb3/simulation.py', 'scan'))
    serialise = _cumulative(stats, 'fake_tb3/prebuilt.py', 'serialize')
    # Handing a message to its connections: rospy.Publisher.publish (the first `publish` of
    # rospy/topics.py: a lock, serialisation, then each connection's write_data), or
    # batched_writes.publish (serialisation and write_data).
    publish = (_cumulative(stats, 'rospy/topics.py', 'publish', first_only=True)
               + _cumulative(stats, batched, 'publish'))
    handover = (_cumulative(stats, 'rospy/impl/tcpros_pubsub.py', 'write_data')
                + _cumulative(stats, batched, 'write_data'))
    # The turns: before, a time.sleep(0) that lets the writer threads run (the simulation thread
    # waits for the interpreter lock meanwhile); today, BatchedConnection.flush's sends. Both
    # wait for subscribers that fall behind.
    turns = (_cumulative(stats, batched, 'maybe_yield') + _cumulative(stats, batched, 'maybe_flush')
             + _cumulative(stats, batched, 'flush', (node, 'spin')))
    sending = _cumulative(stats, batched, 'flush', (batched, 'flush'))
    tf = _cumulative(stats, 'tf2_ros/transform_broadcaster.py', 'sendTransform')
    clock = sum(_cumulative(stats, 'rospy/topics.py', 'publish', (node, caller), first_only=True)
                + _cumulative(stats, batched, 'publish', (node, caller))
                for caller in ('_step_physics', 'publish_clock'))
    in_publishers = sum(_cumulative(stats, node, name) for name in (
        'publish_odometry', 'publish_joint_states', 'publish_imu', '_publish_scans',
        '_step_physics', '_publish_tick'))
    sleep = _cumulative(stats, '~', '<built-in method time.sleep>', (node, 'spin'))
    total = max(value[3] for value in stats.stats.values())
    parts = [('physics (Simulation.step)', physics),
             ('ray cast (Simulation.scans, or .scan of each robot)', raycast),
             ('serialisation (prebuilt serialize)', serialise),
             ('handing the bytes to each connection (write_data)', handover),
             ('the publish() around those two', publish - serialise - handover),
             ('of which TF, all of sendTransform', tf),
             ('of which /clock, all of its publish()', clock),
             ('message building (the rest of the publishing functions)',
              in_publishers - physics - raycast - publish),
             ('sending each connection\'s batch to its socket (flush)', sending),
             ('letting writer threads run, waiting for subscribers', turns - sending),
             ('pacing (time.sleep in the loop)', sleep)]
    parts.append(('the rest (loop, requests)',
                  total - sum(value for name, value in parts if not name.startswith('of which'))))
    return total, parts


def profile(seconds, top, robots, clock):
    core = start_master()
    folder = tempfile.mkdtemp(prefix='fake_tb3_profile_')
    stats_path, cpu_path = os.path.join(folder, 'node.prof'), os.path.join(folder, 'cpu')
    try:
        rospy.init_node('fake_tb3_profile', disable_signals=True)
        name = 'profiled'
        spawns = grid_of_robots(robots)
        if robots == 1:
            spawns[0].update(x_pos=-2.0, y_pos=-0.5)
        rospy.set_param('/use_sim_time', True)
        rospy.set_param('/%s/world' % name, 'turtlebot3_world' if robots == 1 else 'empty')
        rospy.set_param('/%s/real_time_factor' % name, 1000.0)
        rospy.set_param('/%s/robots' % name, spawns)
        node = subprocess.Popen(['/usr/bin/python3', '-c', PROFILED_NODE, stats_path, cpu_path,
                                 clock, '__name:=' + name], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
        counter = TopicCounter(spawns, raw=True)
        cmd_vels = [rospy.Publisher('/%s/cmd_vel' % spawn['name'], Twist, queue_size=1,
                                    latch=True) for spawn in spawns]
        try:
            wait_until(lambda: all(p.get_num_connections() for p in cmd_vels), 60,
                       'the simulator to start', poll=0.1)
            counter.connect()
            wait_until(lambda: len(counter.clock) >= 10, 30, '/clock', poll=0.1)
            twist = Twist()
            twist.angular.z = 0.5
            for cmd_vel in cmd_vels:
                cmd_vel.publish(twist)
            time.sleep(1.0)
            first_wall, first_clock = counter.clock[-1]
            counter.start = first_clock
            time.sleep(seconds)
            last_wall, last_clock = counter.clock[-1]
        finally:
            stop_process_group(node, 30)
            counter.close()
        simulated = (last_clock - first_clock).to_sec()
        factor = simulated / (last_wall - first_wall)
        stats = pstats.Stats(stats_path)
        with open(cpu_path) as cpu_file:
            thread_cpu, process_cpu = (float(value) for value in cpu_file.read().split())
    finally:
        stop_process_group(core, 30)
    total, parts = breakdown(stats)
    # Per simulated second over the whole profiled run (start-up excluded as far as possible:
    # the run's simulated length is the last /clock the node reached).
    run_simulated = max(last_clock.to_sec(), 1e-9)
    print('real-time factor %.1fx over %.1f wall s; simulator CPU: %.2f s in its simulation '
          'thread, %.2f s in all threads (%.0f %% in rospy\'s other threads); load average %.1f'
          % (factor, last_wall - first_wall, thread_cpu, process_cpu,
             100 * (1 - thread_cpu / process_cpu), os.getloadavg()[0]))
    print()
    print('| part of the simulation thread | ms (%s) per simulated second | share |' % clock)
    print('|---|--:|--:|')
    for part, value in parts:
        print('| %s | %.2f | %.0f %% |' % (part, 1e3 * value / run_simulated, 100 * value / total))
    print()
    print('Top %d functions by own time (ms per simulated second):' % top)
    print()
    print('| function | own ms / sim s | calls / sim s |')
    print('|---|--:|--:|')
    rows = sorted(stats.stats.items(), key=lambda item: -item[1][2])
    shown = 0
    for (path, line, function), (_, calls, own, _, _) in rows:
        if function in ('<built-in method time.sleep>',):
            continue  # waiting, not work
        print('| %s (%s:%d) | %.2f | %.0f |' % (function, '/'.join(path.split('/')[-2:]), line,
                                               1e3 * own / run_simulated, calls / run_simulated))
        shown += 1
        if shown == top:
            break
    sys.stdout.flush()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--seconds', type=float, default=8.0, help='wall seconds profiled')
    parser.add_argument('--top', type=int, default=5, help='functions listed')
    parser.add_argument('--robots', type=int, default=1,
                        help='robots (more than one: the bench\'s grid, 1 m apart, empty world)')
    parser.add_argument('--clock', choices=('wall', 'cpu'), default='wall',
                        help='what the profile counts: wall time, or the CPU time of the thread '
                        '(on a busy machine, without the other processes\' turns; waiting then '
                        'counts for nothing)')
    args = parser.parse_args()
    profile(args.seconds, args.top, args.robots, args.clock)


if __name__ == '__main__':
    main()
