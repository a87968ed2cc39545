"""A private ROS master for the tour, launch files started and stopped on it, and small ROS helpers.

The tour is one ROS node (`course_tour`) on its own master, on a free port, so that it never meets a
master the user already runs. Each lab starts its launch files here and stops them with SIGINT, as
Ctrl-C in a terminal would, so the simulators save their pictures at shutdown. roslaunch starts each
node in a session of its own, out of reach of the launch's process group: each launch, and the
tour as a whole, marks the environment of what it starts, and what still carries the mark once
it has been stopped is killed (course_common.process_table).
"""
import os

import rosgraph
import rospy

from course_common.process_table import descendants, new_mark, stop_marked, with_mark
from course_common.processes import free_port
from course_common.waiting import wait_until
from course_testing.processes import LoggedLaunch


ROSCORE_PARAMS = {'/run_id', '/rosdistro', '/rosversion'}


class Launched(LoggedLaunch):
    """One roslaunch process; its output goes to a log file that labs can read back. What it
    started and outlived it is stopped with it (by its mark)."""

    def __init__(self, argv, log_path, env, params_before=()):
        self.params_before = set(params_before)
        self.mark = new_mark('COURSE_TOUR_LAUNCH')
        super().__init__(argv, log_path, with_mark(self.mark, env))

    def stop(self, timeout=20.0):
        try:
            super().stop(timeout)
        finally:
            stop_marked(self.mark)   # a node that outlived its roslaunch


class Session:
    """The tour's master, its output folder, and what the labs start on it."""

    def __init__(self, output_dir):
        self.output_dir = output_dir
        self.log_dir = os.path.join(output_dir, 'logs')
        os.makedirs(self.log_dir, exist_ok=True)
        # In os.environ too: the teleops, Xvfb and rviz that labs start themselves carry it.
        self.mark = new_mark('COURSE_TOUR')
        os.environ.update(with_mark(self.mark, {}))
        self.env = dict(os.environ)
        self.env['PYTHONUNBUFFERED'] = '1'  # print() of the course nodes reaches the log at once
        self._launched = []
        self._master = None

    def __enter__(self):
        uri = 'http://localhost:%d' % free_port()
        self.env['ROS_MASTER_URI'] = uri
        os.environ['ROS_MASTER_URI'] = uri
        self._master = Launched(['roscore', '-p', uri.rsplit(':', 1)[1]],
                                os.path.join(self.log_dir, 'roscore.log'), self.env)
        master = rosgraph.Master('/course_tour')
        wait_until(lambda: self._ours_answers(master), 30, what='the ROS master of the tour')
        # roscore sets /run_id a moment after the master answers; `roslaunch --wait` waits for it.
        wait_until(lambda: master.hasParam('/run_id'), 30, what='roscore to set /run_id')
        rospy.init_node('course_tour', disable_signals=True)
        return self

    def _ours_answers(self, master):
        """The master on the port is our roscore's: the port was free when chosen, not reserved, and
        a master another program started there meanwhile would answer too."""
        if self._master.exited():
            raise RuntimeError('roscore ended before its master answered:\n%s' % self._master.output()[-2000:])
        try:
            return master.getPid() in descendants(self._master.process.pid)
        except Exception:   # not up yet, or no ROS master there
            return False

    def __exit__(self, *exc):
        try:
            self.stop_all()
            rospy.signal_shutdown('tour finished')
            self._master.stop()
        finally:
            stop_marked(self.mark)   # whatever a lab started and did not stop
        return False

    def picture(self, name):
        return os.path.join(self.output_dir, name)

    def launch(self, package, launch_file, env=None, params=None, **args):
        """Start `roslaunch package launch_file name:=value ...` on the tour's master, with `params`
        ({name: value}) set on the master first; like the launch's own, they go when it is stopped."""
        argv = ['roslaunch', '--wait', package, launch_file]
        argv += ['%s:=%s' % (key, value) for key, value in args.items()]
        log_path = os.path.join(self.log_dir, '%02d-%s.log' % (len(os.listdir(self.log_dir)),
                                                              os.path.splitext(launch_file)[0]))
        before = rospy.get_param_names()
        for name, value in (params or {}).items():
            rospy.set_param(name, value)
        launched = Launched(argv, log_path, env or self.env, before)
        self._launched.append(launched)
        return launched

    def stop(self, launched):
        """Stop a launch and remove the parameters that came with it: the master outlives the
        lab, and a simulator started later must not find (say) an old ~canvas_png and write its
        picture over an earlier lab's. roscore's own parameters stay, whenever they appeared."""
        launched.stop()
        self._launched.remove(launched)
        for name in set(rospy.get_param_names()) - launched.params_before:
            if name not in ROSCORE_PARAMS and not name.startswith('/roslaunch/') \
                    and rospy.has_param(name):
                rospy.delete_param(name)

    def stop_all(self):
        """Stop whatever a lab left running (a lab that failed half way), newest first."""
        for launched in reversed(list(self._launched)):
            self.stop(launched)

    @staticmethod
    def call_trigger(service, timeout=15.0):
        """Call a std_srvs/Trigger service once it exists; returns its message (a saved file's path)."""
        from std_srvs.srv import Trigger
        rospy.wait_for_service(service, timeout)
        response = rospy.ServiceProxy(service, Trigger)()
        if not response.success:
            raise RuntimeError('%s failed: %s' % (service, response.message))
        return response.message
