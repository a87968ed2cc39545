"""One module per lab: CRITERIA (the criterion ids it checks, each with the rubric settings its
check reads), static_checks(session) (no ROS) and run_checks(session) (against the simulators, on
the session's master), each returning {criterion id: Verdict}."""
from course_grader.labs import move_turtlebot3, my_turtle, ros_exercises

LABS = {lab.__name__.rsplit('.', 1)[1]: lab for lab in (move_turtlebot3, my_turtle, ros_exercises)}
