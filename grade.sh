#!/usr/bin/env bash
# Grades a class's submissions of a lab against the simulators: ./grade.sh --help
#   ./grade.sh move_turtlebot3 submissions/*.zip --out grades      (each student in a container)
#   ./grade.sh my_turtle alice/ bob/ --no-container                 (no isolation: trusted code only)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$ROOT/tools/setup.sh"
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"
# The image only when it will be used: a class to grade in containers (not --help, not a usage error).
if [[ $# -ge 2 && " $* " != *" --no-container "* && " $* " != *" --help "* && " $* " != *" -h "* && -z "${COURSE_GRADER_IMAGE:-}" ]]; then
    # shellcheck source=tools/docker.sh
    source "$ROOT/tools/docker.sh"
    course_docker_engine || { echo "grade: no Docker engine; grade with --no-container only code you trust" >&2; exit 2; }
    image=$(course_docker_image bookworm) || { echo "grade: the course's Docker image could not be made" >&2; exit 2; }
    # The image's id, not its tag: the tag may be rebuilt by someone else while we grade.
    COURSE_GRADER_IMAGE=$(docker image inspect -f '{{.Id}}' "$image")
    export COURSE_GRADER_IMAGE
fi
# Not exec: the EXIT trap of tools/docker.sh must still stop a dockerd it started.
rosrun course_grader grade "$@"
