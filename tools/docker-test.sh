#!/usr/bin/env bash
# Builds the image from docker/ and runs the test command inside it (as the non-root user `student`).
#
# Needs root on the host the first time (installs docker.io and debootstrap). Starts its own dockerd
# (vfs storage, no iptables, no bridge: containers use the host network) with its own data root
# unless DOCKER_HOST already points at a running engine, makes the debian:bookworm base image with
# debootstrap when it is missing (no image registry is reachable), and stops the daemon it started.
# Environment: COURSE_DOCKER_ROOT (default /var/tmp/course-docker) holds the engine's data.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DATA="${COURSE_DOCKER_ROOT:-/var/tmp/course-docker}"
IMAGE=ros-course:test
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

for tool in docker:docker.io dockerd:docker.io debootstrap:debootstrap; do
    if ! command -v "${tool%%:*}" >/dev/null; then
        echo "docker-test: installing ${tool#*:}"
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${tool#*:}"
    fi
done

started_pid=""
stop_daemon() {
    if [ -n "$started_pid" ]; then
        kill "$started_pid" 2>/dev/null || true
        for _ in $(seq 100); do kill -0 "$started_pid" 2>/dev/null || break; sleep 0.1; done
    fi
}
trap stop_daemon EXIT

if [ -z "${DOCKER_HOST:-}" ]; then
    mkdir -p "$DATA"
    export DOCKER_HOST="unix://$DATA/docker.sock"
    if ! docker version >/dev/null 2>&1; then
        echo "docker-test: starting dockerd (data in $DATA)"
        dockerd --data-root "$DATA/data" --exec-root "$DATA/exec" --pidfile "$DATA/dockerd.pid" \
                --host "$DOCKER_HOST" --storage-driver=vfs --iptables=false --ip-masq=false \
                --bridge=none > "$DATA/dockerd.log" 2>&1 &
        started_pid=$!
        for _ in $(seq 300); do docker version >/dev/null 2>&1 && break; sleep 0.2; done
        docker version >/dev/null 2>&1 || { tail -n 20 "$DATA/dockerd.log"; echo "docker-test: dockerd did not start" >&2; exit 1; }
    fi
fi

if ! docker image inspect debian:bookworm >/dev/null 2>&1; then
    echo "docker-test: making the debian:bookworm base image with debootstrap"
    rootfs="$DATA/rootfs"
    rm -rf "$rootfs"
    debootstrap --variant=minbase bookworm "$rootfs" http://deb.debian.org/debian > "$DATA/debootstrap.log" 2>&1 \
        || { tail -n 20 "$DATA/debootstrap.log"; exit 1; }
    tar -C "$rootfs" -c . | docker import - debian:bookworm
    rm -rf "$rootfs"
fi

echo "docker-test: building $IMAGE"
docker build --network host -t "$IMAGE" -f "$ROOT/docker/Dockerfile" "$ROOT" > "$DATA/build.log" 2>&1 \
    || { tail -n 40 "$DATA/build.log"; echo "docker-test: docker build failed" >&2; exit 1; }
echo "docker-test: running the tests in the container (user $(docker run --rm "$IMAGE" id -un))"
docker run --rm --network host "$IMAGE" ./test.sh
