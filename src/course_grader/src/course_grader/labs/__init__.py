"""One module per lab: CRITERIA (the criterion ids it checks, each with the rubric settings its
check reads), static_checks(session) (no ROS) and run_checks(session) (against the simulators, on
the session's master), each returning {criterion id: Verdict}. A session imports only its own lab
(the turtlesim labs' modules import roslaunch, a second of a session's start)."""
import importlib

LABS = ('move_turtlebot3', 'my_turtle', 'ros_exercises')


def lab_module(name):
    """The module of the lab `name` (one of LABS)."""
    return importlib.import_module('course_grader.labs.' + name)
