#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image of the lab @LAB@
# (made by `rosrun course_grader gradescope_bundle @LAB@ ZIP`; see the course's docs/grading.md).
# The course (ROS 1 from Debian's packages, the workspace built) is either this image itself, or,
# on Gradescope's base image, the course image's root in /srv/ros-course (the bundle's Dockerfile).
set -euo pipefail
course=/home/student/course
root=/srv/ros-course
if [ ! -f "$course/tools/env.sh" ] && [ -f "$root$course/tools/env.sh" ]; then
    rm -rf "$root/autograder/source"
    mkdir -p "$root/autograder"
    cp -R /autograder/source "$root/autograder/source"
    cp /autograder/source/run_autograder "$root/autograder/run_autograder"
    exec chroot "$root" bash /autograder/source/setup.sh
fi
if [ ! -f "$course/tools/env.sh" ]; then
    echo "setup.sh: the course is not in this image ($course, $root$course): Gradescope's own base images cannot install it (ROS 1 from Debian 12 or 13's packages); build the image of the bundle's Dockerfile and name it in the Manual Docker Configuration (docs/grading.md, Gradescope)" >&2
    exit 1
fi
# run_autograder grades as root from the course's tree, the student's side as the user student:
# that user must not be able to change the tree (or rename it away), nor read this bundle.
chown -R root:root /home/student
chmod 755 /home/student
chmod -R go= /autograder/source
