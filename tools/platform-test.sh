#!/usr/bin/env bash
# CI, after tools/grade-test.sh: the platforms' side of the grading run here as the platforms run it
# (src/course_grader/test/platforms_in_containers.py): the GitHub Classroom workflow's steps in
# order on example students and bad pushes, and Gradescope's run_autograder, in the grading image
# the platforms are given (ros-course-grader:bookworm), after a check that it holds what grading
# needs and no more (tools/grade-test.sh --platforms).
# Usage: tools/platform-test.sh [pytest options]
exec "$(dirname "${BASH_SOURCE[0]}")/grade-test.sh" --platforms -s "$@"
