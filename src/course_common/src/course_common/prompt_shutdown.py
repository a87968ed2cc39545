"""rospy's shutdown without its half-second wait.

rospy.signal_shutdown() ends by joining the node's registration thread, which sees the shutdown
flag only when its wait for work times out (RegManager.run: cond.wait(0.5)): a Python node stops
about 0.6 s after Ctrl-C, where a C++ one (the original turtlesim) stops at once. install(), after
rospy.init_node(), adds a shutdown hook (run once the flag is set) that wakes that thread, so it ends
and rospy.signal_shutdown() returns after its own short sleep (0.1 s)."""
import rospy.core
from rospy.impl.registration import RegManager, get_registration_listeners


def registration_managers():
    """The node's RegManager(s): init_node() returns once it registered, and so listens by then."""
    return [listener for listener in get_registration_listeners().listeners if isinstance(listener, RegManager)]


def install(managers=None):
    """Call once after rospy.init_node()."""
    managers = registration_managers() if managers is None else managers

    def wake(_reason):
        for manager in managers:
            with manager.cond:
                manager.cond.notify_all()
    rospy.core.add_shutdown_hook(wake)
