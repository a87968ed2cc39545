#!/usr/bin/env bash
# Builds the image from docker/ and runs the test command inside it (as the non-root user `student`).
# Usage: tools/docker-test.sh [SUITE]      (Debian suite of the image: trixie, the default, or bookworm)
# tools/docker.sh reaches or starts the engine and makes the image; a dockerd started here is stopped.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine
image=$(course_docker_image "${1:-trixie}")
echo "docker-test: running the tests in $image (user $(docker run --rm "$image" id -un))"
docker run --rm --network host "$image" ./test.sh
