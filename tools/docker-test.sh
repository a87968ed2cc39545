#!/usr/bin/env bash
# Builds the image from docker/ and runs the test command inside it (as the non-root user `student`),
# then checks that the image serves the browser view of a lab to the outside (tools/docker-view-check.py)
# and runs the students' Docker page, docs/student-docker.md, as written (tools/student-docker-check.py).
# Usage: tools/docker-test.sh [SUITE] [--no-suite]
#   SUITE       Debian suite of the image: trixie, the default, or bookworm
#   --no-suite  the image's own checks only, not ./test.sh in it (CI, for the image of the suite whose
#               every test its host has just run: docs/docker-and-ci.md#ci)
# When ./test.sh fails in the image, its logs (build/test_logs in the image) are copied to
# build/docker-test-logs-SUITE.
# tools/docker.sh reaches or starts the engine and makes the image; a dockerd started here is stopped.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
suite=trixie
run_suite=yes
for argument in "$@"; do
    case "$argument" in
        --no-suite) run_suite=no ;;
        -*) echo "docker-test: unknown option $argument (usage: tools/docker-test.sh [SUITE] [--no-suite])" >&2; exit 2 ;;
        *) suite=$argument ;;
    esac
done
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine
image=$(course_docker_image "$suite")
if [ "$run_suite" = yes ]; then
    echo "docker-test: running the tests in $image (user $(docker run --rm "$image" id -un))"
    # The container is kept until its logs are out: a step that fails in it says why only there.
    container=$(docker create --network host "$image" ./test.sh)
    # A run cancelled meanwhile (Ctrl-C, a CI runner's SIGTERM) removes it too, instead of leaving it
    # stopped in the course's data root; a dockerd started here is stopped after it, as before.
    trap 'docker rm --force "$container" > /dev/null 2>&1; course_docker_stop' EXIT
    status=0
    docker start --attach "$container" || status=$?
    if [ "$status" != 0 ]; then
        logs="$ROOT/build/docker-test-logs-$suite"
        rm -rf "$logs" && mkdir -p "$ROOT/build"
        docker cp "$container:/home/student/course/build/test_logs" "$logs" > /dev/null \
            && echo "docker-test: the tests failed in $image; their logs are in ${logs#"$ROOT"/}" >&2
    fi
    docker rm "$container" > /dev/null
    trap course_docker_stop EXIT
    [ "$status" = 0 ] || exit "$status"
else
    echo "docker-test: $image built; its tests not run here (--no-suite)"
fi
# The browser view as the image serves it (docker/entrypoint.sh), seen from outside the container.
/usr/bin/python3 "$ROOT/tools/docker-view-check.py" "$image"
# The students' page: their container, workspace, terminals, restarts (docs/student-docker.md).
/usr/bin/python3 "$ROOT/tools/student-docker-check.py" "$image"
