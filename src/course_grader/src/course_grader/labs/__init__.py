"""One module per lab: its table RUNS (common.LabRun: each run after the build, with the criteria it
decides and the rubric settings each reads, and what it takes of the wall limit) and
STATIC_CRITERIA (those decided without a run); CRITERIA, the criterion ids it checks with the
settings, derived from both; static_checks(session) (no ROS) and run_checks(session) (RUNS, against
the simulators, on the session's master), each returning {criterion id: Verdict}. A session imports
only its own lab (the turtlesim labs' modules import roslaunch, a second of a session's start)."""
import importlib

from course_grader import wall_limit

LABS = ('move_turtlebot3', 'my_turtle', 'ros_exercises')


def lab_module(name):
    """The module of the lab `name` (one of LABS)."""
    return importlib.import_module('course_grader.labs.' + name)


def wall_limit_of(rubric):
    """How long a session grading with `rubric` may last (wall_limit.seconds): the rubric's limits
    and the kinds of each run of its lab's table (RUNS). Imports the lab's module (ROS)."""
    return wall_limit.seconds(rubric.limits, [kind for run in lab_module(rubric.lab).RUNS for kind in run.kinds])
