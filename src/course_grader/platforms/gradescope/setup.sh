#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image of the lab @LAB@
# (made by `rosrun course_grader gradescope_bundle @LAB@ ZIP`; see the course's docs/grading.md).
# The image must be the course's: ROS 1 from Debian's packages and the workspace built.
set -euo pipefail
course=/home/student/course
if [ ! -f "$course/tools/env.sh" ]; then
    echo "setup.sh: the course is not in this image ($course): Gradescope's own base images cannot install it (ROS 1 from Debian 12 or 13's packages); name the course's image in the Manual Docker Configuration (docs/grading.md, Gradescope)" >&2
    exit 1
fi
# run_autograder grades as root from the course's tree, the student's side as the user student:
# that user must not be able to change the tree (or rename it away), nor read this bundle.
chown -R root:root /home/student
chmod 755 /home/student
chmod -R go= /autograder/source 2>/dev/null || true
