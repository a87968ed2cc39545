"""Grading a class's submissions of a course lab against the course's simulators."""

# What `python3 -m course_grader.turtlesim_launch describe` begins the line of each launch file with
# (labs.turtlesim_runs reads it): here, so that the grader reads it without importing roslaunch.
TURTLESIM_NODES_PREFIX = 'turtlesim nodes: '
