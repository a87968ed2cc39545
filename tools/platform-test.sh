#!/usr/bin/env bash
# CI, after tools/grade-test.sh: the platforms' side of the grading run here as the platforms run it
# (src/course_grader/test/platforms_in_containers.py): the GitHub Classroom workflow's steps in
# order on example students and bad pushes, and Gradescope's run_autograder in the course's image.
# Usage: tools/platform-test.sh [pytest options]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
"$ROOT/tools/setup.sh"
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine
image=$(course_docker_image bookworm)
# By id: the tag may move meanwhile.
COURSE_GRADER_IMAGE=$(docker image inspect -f '{{.Id}}' "$image")
export COURSE_GRADER_IMAGE
# Not exec: the EXIT trap of tools/docker.sh must still stop a dockerd it started.
/usr/bin/python3 -m pytest -v -s -p no:cacheprovider "$ROOT/src/course_grader/test/platforms_in_containers.py" "$@"
