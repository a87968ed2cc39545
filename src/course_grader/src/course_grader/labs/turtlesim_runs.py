"""The turtlesim labs' runs: the student's launch file on the student's side with its turtlesim
node(s) left out (course_grader.turtlesim_launch), and in their place the course's turtlesim,
started by the grader on the trusted side (the course's environment only) with what the launch file
gives it: its name, namespace, remappings and private parameters. With a real-time factor,
turtlesim runs on its own simulated clock that much faster than real time, and so do the student's
nodes (/use_sim_time); with lock_step too, each tick waits for the student's answer (turtlesim's
~lock_step), so that a closed loop meets the same simulated delays at any factor and load."""
import functools
import json
import os

import rosgraph
import rosgraph.names
import roslib.packages
import rospy
from rosgraph_msgs.msg import Clock

from turtlesim.msg import Pose

from course_checks.recorded import PublisherLook, RecordedTopic, Records
from course_checks.robot import left_the_graph, node_names
from course_checks.verdict import Verdict
from course_common.waiting import wait_for
from course_grader import bags, wall_limit
from course_grader.labs.common import faked
from course_grader import TURTLESIM_NODES_PREFIX as PREFIX
from course_common.processes import together

MAX_TURTLESIMS = 3           # turtlesim nodes of one launch file started for it, at most
MAX_PARAMS = 50              # of one turtlesim node's private parameters passed on, at most
GRADERS_PARAMS = ('canvas_png', 'real_time_factor', 'clock_rate', 'lock_step')   # given by the grader alone
LAUNCHER = ['/usr/bin/python3', '-s', '-m', 'course_grader.turtlesim_launch']


def _legal(name):
    return (isinstance(name, str) and rosgraph.names.is_legal_name(name) and not name.startswith('_')
            and '__' not in name and ':=' not in name)


def _node(declared):
    """A turtlesim node as described on the student's side, checked (the description is the
    student's side's word: a special name such as `__log` or `__master` is never passed on)."""
    if not isinstance(declared, dict) or not _legal(declared.get('name')) or declared['name'] in ('/', ''):
        return None
    remaps = [tuple(pair) for pair in declared.get('remaps', []) if isinstance(pair, list) and len(pair) == 2
              and all(_legal(name) for name in pair)]
    params = declared.get('params')
    params = sorted(params.items())[:MAX_PARAMS] if isinstance(params, dict) else []
    params = {name: value for name, value in params
              if _legal(name) and not name.startswith('/') and name not in GRADERS_PARAMS}
    return {'name': rosgraph.names.canonicalize_name(declared['name']), 'remaps': remaps, 'params': params}


def describe_launches(session, launches):
    """What each (launch_file, args) of the student's package declares of turtlesim, read by
    roslaunch's loader on the student's side (as the student's user, with the course's environment
    and the overlay's package paths only: nothing of the build runs in it) in one run. Keeps, in
    session.turtlesim_nodes, for each: the turtlesim nodes, or a sentence saying why none."""
    side = session.student_side
    argv = LAUNCHER + ['describe']
    for index, (launch_file, args) in enumerate(launches):
        argv += (['--'] if index else []) + [session.rubric.package, launch_file] + list(args)
    # Where roslaunch looks for the package and its files: the overlay's workspaces first.
    env = dict(os.environ, HOME=side.home, ROS_HOME=side.env['ROS_HOME'],
               **{name: side.env.get(name, '') for name in ('ROS_PACKAGE_PATH', 'CMAKE_PREFIX_PATH')})
    try:
        lines = side.run(argv, wall_limit.STEP_SECONDS, env=env, cwd='/').decode(errors='replace').splitlines()
    except Exception as error:   # noqa: B902 (a time-out, a failure: no turtlesim for any of them)
        lines = ['roslaunch could not read the launch files (%s)' % type(error).__name__]
    for index, launch in enumerate(launches):
        line = lines[index] if index < len(lines) else 'roslaunch could not read it'
        key = (launch[0], tuple(launch[1]))
        if line.startswith(PREFIX):
            try:
                nodes = [_node(declared) for declared in json.loads(line[len(PREFIX):])]
                session.turtlesim_nodes[key] = [node for node in nodes if node][:MAX_TURTLESIMS]
                continue
            except ValueError:
                line = 'roslaunch could not read it'
        session.turtlesim_nodes[key] = line[:300]


class SimulatedClock:
    """Calls `callback` every `period` seconds of the simulated clock turtlesim publishes on
    /clock (the grader's own rospy node keeps the wall clock)."""

    def __init__(self, period, callback):
        self.period = period
        self.callback = callback
        self.next_time = None
        self.subscriber = rospy.Subscriber('/clock', Clock, self._tick, queue_size=10)

    def _tick(self, message):
        now = message.clock.to_sec()
        if self.next_time is None or now >= self.next_time or now < self.next_time - 2 * self.period:
            self.next_time = now + self.period
            self.callback()

    def shutdown(self):
        self.subscriber.unregister()


class TurtlesimLaunch:
    """`roslaunch PACKAGE launch_file args` as the lab runs it: its turtlesim node(s) started on the
    trusted side (turtlesim's lines logged to <log>_turtlesim.txt, its canvas kept as `picture` when
    it stops), the rest of the launch file on the student's side (logged to <log>.log). With `only`
    (an executable of the package), that executable's node(s) of the file alone, and no turtlesim."""

    def __init__(self, session, launch_file, args, log_name, real_time_factor=None, picture=None, lock_step=False,
                 only=None):
        self.session = session
        self.command = 'roslaunch %s %s%s' % (session.rubric.package, launch_file, ''.join(' ' + arg for arg in args))
        key = (launch_file, tuple(args))
        if key not in session.turtlesim_nodes:
            describe_launches(session, [(launch_file, args)])
        declared = session.turtlesim_nodes[key]
        self.declared = declared if isinstance(declared, list) and not only else []
        self.unread = None if isinstance(declared, list) else declared
        self.sim_log = os.path.splitext(log_name)[0] + '_turtlesim.txt'
        self.name = os.path.splitext(log_name)[0]   # of its bag, <name>.bag (course_grader.bags)
        self.marks = bags.Marks()   # the moments the checks judged
        self.recorded = []       # (record file, turtlesim's full name) of each turtlesim started
        self.simulators = {}     # full name: (its Launch, its XML-RPC URI once it registered)
        # What the turtlesims did, as they recorded it (the evidence of the run), and the nodes the
        # master lists as publishers of the turtles' pose topics beside them.
        self.records = Records()
        self.publishers = PublisherLook()
        self.run = None
        self.stopped = False
        self.trouble = None
        # The student's nodes read /use_sim_time when they start: set before anything starts.
        rospy.set_param('/use_sim_time', real_time_factor is not None)
        for index, node in enumerate(self.declared):
            self.start_turtlesim(node, real_time_factor, picture if index == 0 else None, wait=False,
                                 lock_step=lock_step)
        # The rest starts beside turtlesim, as roslaunch starts a file's nodes: none waits for another.
        self.known_nodes = node_names()
        self.run = session.student(LAUNCHER + ['launch'] + (['--only', '%s/%s' % (session.rubric.package, only)]
                                                            if only else [])
                                   + [session.rubric.package, launch_file] + list(args), log_name)
        for name in list(self.simulators):
            self.wait_for_turtlesim(name)

    def start_turtlesim(self, node, real_time_factor=None, picture=None, wait=True, lock_step=False):
        """The course's turtlesim as `node` declares it (name, remappings, private parameters);
        with `wait`, returns once it serves (or after start_seconds)."""
        name = node['name']
        try:
            rospy.delete_param(name)   # what an earlier run left under its name
        except KeyError:
            pass
        for param, value in node['params'].items():
            rospy.set_param(name + '/' + param, value)
        # The grader's settings on turtlesim's command line: a parameter, any node could set before
        # turtlesim reads it (the student's launch file starts beside it).
        settings = ['--canvas-png', self.session.picture(picture) if picture else '']
        if real_time_factor is not None:
            settings += ['--real-time-factor', str(float(real_time_factor))] + (['--lock-step'] if lock_step else [])
        namespace, base = rosgraph.names.namespace(name), name.rsplit('/', 1)[-1]
        executable = roslib.packages.find_node('turtlesim', 'turtlesim_node')[0]   # the course's (our environment)
        log = self.sim_log if not self.simulators else '%s_%d.txt' % (self.sim_log[:-4], len(self.simulators))
        record = self.session.record_path(log[:-4])
        launch = self.session.trusted([executable, '__name:=' + base, '__ns:=' + namespace]
                                      + ['%s:=%s' % pair for pair in node['remaps']] + settings, log, record=record)
        self.simulators[name] = (launch, None)
        self.records.add(record)
        self.recorded.append((record, name))
        self.publishers.owners.add(name)
        if wait:
            self.wait_for_turtlesim(name)

    def wait_for_turtlesim(self, name):
        """Waits until turtlesim `name` serves (or start_seconds), and notes the XML-RPC URI the
        master gives for its name: a node that takes that name later changes it. One that took it
        before shut ours down (the master shuts the older down): ours has ended, which is seen too."""
        launch = self.simulators[name][0]
        master = rosgraph.Master(rospy.get_name())

        def serving():
            try:
                master.lookupService(rosgraph.names.ns_join(rosgraph.names.namespace(name), 'clear'))
                return master.lookupNode(name)
            except Exception:   # noqa: B902 (not yet)
                return None
        wait_for(serving, self.session.rubric.limits['start_seconds'], gave_up=launch.ended)
        self.simulators[name] = (launch, serving())

    def poses(self, turtle):
        """The turtle's poses as the run's turtlesim recorded them (pose topic /TURTLE/pose); a node
        that publishes on that topic is named (impostors)."""
        topic = '/%s/pose' % turtle
        self.publishers.topics.add(topic)
        return RecordedTopic(self.records, topic, Pose)

    def pose_times(self, turtle):
        """The simulated time (s) of each pose of the turtle recorded so far, in the order of poses()."""
        return [entry.sim_time for entry in self.records.entries('/%s/pose' % turtle)]

    def mark(self, t, what, criterion):
        """A moment the checks judged, at `t` simulated seconds (kept beside the run's bag)."""
        self.marks.add(t, what, criterion)

    def impostors(self):
        """{pose topic: nodes} of the nodes other than the turtlesims that the master listed as
        publishers of a turtle's pose topic watched (poses())."""
        return {topic: sorted(nodes) for topic, nodes in sorted(self.publishers.look(0).items())}

    def service_calls(self):
        """[(service, caller as the caller says)] of the turtlesims' services, as they noted them."""
        return self.records.service_calls()

    def turtles(self):
        """The turtles of the turtlesim(s) now, as they recorded them (None before they told)."""
        told = self.records.events('turtles')
        return set(told[-1]['names']) if told else None

    @property
    def simulator_lines(self):
        return [line for launch, _ in self.simulators.values() for line in launch.lines]

    def _replaced(self):
        """Why a turtlesim of the run is not the one the grader started any more, or None."""
        master = rosgraph.Master(rospy.get_name())
        for name, (launch, uri) in sorted(self.simulators.items()):
            try:
                now = master.lookupNode(name)
            except Exception:   # noqa: B902 (unknown to the master: gone)
                now = None
            if launch.ended() or now != uri:
                return ('not judged: the course\'s turtlesim %s stopped or was replaced during the run, before '
                        'the grader stopped it (see %s): a node of the submission took its name or shut it down'
                        % (name, self.sim_log))
        return None

    def finish(self):
        """Notes whether a simulator was stopped or replaced before now (`trouble`, a sentence),
        then stops the student's side and the simulators together (turtlesim saves its canvas)."""
        if self.stopped:
            return
        self.stopped = True
        self.trouble = self._replaced()
        stops = [functools.partial(launch.stop, 15) for launch, _ in self.simulators.values()]
        if self.run:
            # Once the nodes it started have left the graph (roscpp and rospy leave it first on
            # Ctrl-C), what is left of the student's roslaunch is its own exit, 0.3 s: not waited for.
            started = node_names() - self.known_nodes - set(self.simulators)
            stops.append(functools.partial(self.run.stop, self.session.rubric.limits['stop_seconds'],
                                           functools.partial(left_the_graph, started) if started else None))
        together(*stops)
        self.publishers.look(0)
        self.publishers.close()
        if self.recorded:
            self.session.keep_run(self.name, lambda: [message for record, name in self.recorded
                                                      for message in bags.turtlesim_messages(bags.read_record(record), name)])

    def judged(self, outcomes):
        """The outcomes of the run, judged on what the turtlesims recorded, unless a turtlesim the
        grader started stopped or was replaced during it, or a node published on a turtle's pose
        topic beside them: then each fails, saying so. Stops the run; the moments marked are kept
        beside its bag."""
        self.finish()
        if self.recorded:   # a run with a turtlesim has a bag
            self.session.keep_marks(self.name, self.marks)
        if self.trouble:
            return {criterion_id: Verdict(False, self.trouble) for criterion_id in outcomes}
        impostors = self.impostors()
        if impostors:
            return faked(outcomes, impostors, ', '.join(sorted(self.simulators)) or 'turtlesim')
        return outcomes
