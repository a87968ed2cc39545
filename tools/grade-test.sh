#!/usr/bin/env bash
# CI, after tools/docker-test.sh: grades the example classes (examples/grading/) with ./grade.sh in
# containers, the hostile examples included, and checks every score and feedback sentence.
# Usage: tools/grade-test.sh [pytest options]
#        tools/grade-test.sh --platforms [pytest options]   (what tools/platform-test.sh runs)
set -euo pipefail
tests=classes_in_containers.py
if [ "${1:-}" = --platforms ]; then
    tests=platforms_in_containers.py
    shift
fi
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
"$ROOT/tools/setup.sh"
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine
image=$(course_docker_image bookworm)
# Made once here; every ./grade.sh of the tests uses it (by id: the tag may move meanwhile).
COURSE_GRADER_IMAGE=$(docker image inspect -f '{{.Id}}' "$image")
export COURSE_GRADER_IMAGE
# Not exec: the EXIT trap of tools/docker.sh must still stop a dockerd it started.
/usr/bin/python3 -m pytest -v -p no:cacheprovider "$ROOT/src/course_grader/test/$tests" "$@"
