"""How long one grading session may last: the sum of what each of its steps may take, by the
rubric's limits and the kinds of its lab's runs (the table RUNS in labs/<lab>.py), plus a margin for
the grader's own work. ./grade.sh and grade_platform stop a session beyond it, and then every
criterion fails with that one reason: so it must never come before the steps' own limits, which
give each run its own verdict (pure: no ROS; labs.wall_limit_of gives it a lab's runs)."""

# The grader's steps on the student's side whose limit is the grader's, not the rubric's: the
# overlay's environment read after the build (session.build) and roslaunch's reading of the launch
# files (turtlesim_runs.describe_launches) each stop after this.
STEP_SECONDS = 60
# The session's own start (its imports, the rubric, the static checks), the build's stop (5 s, and
# 5 more for its output), what is left of the build stopped, the result written and sent.
SESSION_MARGIN = 30
# Each run's own work beside the student's nodes: its simulator's start and stop, the last messages
# heard, what is left of the run stopped.
RUN_MARGIN = 15

NODES = 'nodes'        # the student's script or launch file: start_seconds, run_seconds, stop_seconds
READING = 'reading'    # roslaunch's reading of the student's launch files: STEP_SECONDS


def run_seconds(run, limits):
    """The most one run (NODES or READING) may take, with `limits` (a rubric's)."""
    if run == READING:
        return STEP_SECONDS
    return limits['start_seconds'] + limits['run_seconds'] + limits['stop_seconds'] + RUN_MARGIN


def seconds(limits, runs):
    """The wall limit of a session with the rubric's `limits` that does `runs` after the build:
    the build, the overlay's environment read, each run, and SESSION_MARGIN."""
    return (SESSION_MARGIN + limits['build_seconds'] + STEP_SECONDS
            + sum(run_seconds(run, limits) for run in runs))
