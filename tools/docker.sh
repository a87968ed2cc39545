# Sourced by the scripts that use Docker (tools/docker-test.sh, grade.sh): one way to reach an engine
# and one way to make the course image.
#   course_docker_engine        an engine answers at $DOCKER_HOST afterwards; if none did, starts our
#                               own dockerd (data in $COURSE_DOCKER_ROOT) and stops it, by PID, on EXIT
#   course_docker_image SUITE   builds ros-course:SUITE from docker/Dockerfile (making the debian:SUITE
#                               base image with debootstrap when missing) and prints the image's name
# Needs root the first time (installs docker.io and debootstrap).
_course_docker_top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COURSE_DOCKER_ROOT="${COURSE_DOCKER_ROOT:-/var/tmp/course-docker}"
_course_dockerd_pid=""

_course_docker_tools() {
    local tool
    for tool in docker:docker.io dockerd:docker.io debootstrap:debootstrap; do
        if ! command -v "${tool%%:*}" >/dev/null; then
            echo "docker: installing ${tool#*:}" >&2
            apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${tool#*:}" >&2
        fi
    done
}

course_docker_stop() {
    [ -n "$_course_dockerd_pid" ] || return 0
    kill "$_course_dockerd_pid" 2>/dev/null || true
    local _
    for _ in $(seq 100); do kill -0 "$_course_dockerd_pid" 2>/dev/null || break; sleep 0.1; done
    _course_dockerd_pid=""
}

course_docker_engine() {
    _course_docker_tools
    if [ -z "${DOCKER_HOST:-}" ]; then
        mkdir -p "$COURSE_DOCKER_ROOT"
        export DOCKER_HOST="unix://$COURSE_DOCKER_ROOT/docker.sock"
    fi
    docker version >/dev/null 2>&1 && return 0
    echo "docker: starting dockerd (data in $COURSE_DOCKER_ROOT)" >&2
    dockerd --data-root "$COURSE_DOCKER_ROOT/data" --exec-root "$COURSE_DOCKER_ROOT/exec" \
            --pidfile "$COURSE_DOCKER_ROOT/dockerd.pid" --host "$DOCKER_HOST" --storage-driver=overlay2 \
            --iptables=false --ip-masq=false --bridge=none > "$COURSE_DOCKER_ROOT/dockerd.log" 2>&1 &
    _course_dockerd_pid=$!
    trap course_docker_stop EXIT
    local _
    for _ in $(seq 300); do docker version >/dev/null 2>&1 && return 0; sleep 0.2; done
    tail -n 20 "$COURSE_DOCKER_ROOT/dockerd.log" >&2
    echo "docker: dockerd did not start (log: $COURSE_DOCKER_ROOT/dockerd.log)" >&2
    return 1
}

course_docker_image() {
    local suite="${1:-bookworm}" image="ros-course:${1:-bookworm}"
    if ! docker image inspect "debian:$suite" >/dev/null 2>&1; then
        echo "docker: making the debian:$suite base image with debootstrap" >&2
        local rootfs="$COURSE_DOCKER_ROOT/rootfs-$suite"
        rm -rf "$rootfs"
        debootstrap --variant=minbase "$suite" "$rootfs" > "$COURSE_DOCKER_ROOT/debootstrap-$suite.log" 2>&1 \
            || { tail -n 20 "$COURSE_DOCKER_ROOT/debootstrap-$suite.log" >&2; return 1; }
        tar -C "$rootfs" -c . | docker import - "debian:$suite" >/dev/null
        rm -rf "$rootfs"
    fi
    echo "docker: building $image" >&2
    docker build --network host --build-arg "SUITE=$suite" -t "$image" -f "$_course_docker_top/docker/Dockerfile" \
        "$_course_docker_top" > "$COURSE_DOCKER_ROOT/build-$suite.log" 2>&1 \
        || { tail -n 40 "$COURSE_DOCKER_ROOT/build-$suite.log" >&2; echo "docker: docker build failed" >&2; return 1; }
    echo "$image"
}
