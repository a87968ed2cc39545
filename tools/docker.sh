# Sourced by the scripts that use Docker (tools/docker-test.sh, grade.sh): one way to reach an engine
# and one way to make the course image.
#   course_docker_engine        an engine answers at $DOCKER_HOST afterwards; if none did, starts our
#                               own dockerd (data in $COURSE_DOCKER_ROOT; overlay2, or vfs where a trial
#                               container cannot run on overlay2) and stops it, by PID, on EXIT
#   course_docker_image SUITE   builds ros-course:SUITE from docker/Dockerfile (making the debian:SUITE
#                               base image with debootstrap when missing) and prints the image's name;
#                               COURSE_IMAGE_NAME=name gives the image another name than ros-course
#                               (two checkouts building side by side on one engine)
#   course_docker_grading_image SUITE
#                               the same for the grading image, ros-course-grader:SUITE (the Dockerfile's
#                               target grader: what a grading needs and no more, the first layers of
#                               ros-course:SUITE; NAME-grader with COURSE_IMAGE_NAME=NAME)
# The Debian archive (and apt's proxy, if any) are the ones this machine's own apt uses, so a machine
# behind a mirror or a proxy makes its images the same way. Needs root the first time (installs
# docker.io and debootstrap).
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

# Starts our dockerd with storage driver $1; true once it answers.
_course_dockerd_start() {
    echo "docker: starting dockerd ($1, data in $COURSE_DOCKER_ROOT)" >&2
    # In a process group of its own (job control on for this start): a Ctrl-C or a CI runner's signal
    # to the caller's group leaves it to course_docker_stop, after the caller removed its containers.
    local monitor=${-//[^m]/}
    set -m
    dockerd --data-root "$COURSE_DOCKER_ROOT/data" --exec-root "$COURSE_DOCKER_ROOT/exec" \
            --pidfile "$COURSE_DOCKER_ROOT/dockerd.pid" --host "$DOCKER_HOST" --storage-driver="$1" \
            --iptables=false --ip-masq=false --bridge=none > "$COURSE_DOCKER_ROOT/dockerd-$1.log" 2>&1 &
    _course_dockerd_pid=$!
    disown "$_course_dockerd_pid"   # no job notice when it ends: course_docker_stop waits for it
    [ -n "$monitor" ] || set +m
    trap course_docker_stop EXIT
    local _
    for _ in $(seq 300); do
        docker version >/dev/null 2>&1 && return 0
        kill -0 "$_course_dockerd_pid" 2>/dev/null || break
        sleep 0.2
    done
    course_docker_stop
    return 1
}

# True when a container runs: a trial image of the host's own /bin/true and the libraries it loads.
_course_docker_trial_run() {
    local files
    files=$(ldd /bin/true | grep -o '/[^ ]*' | sed 's|^/||')
    tar -C / -ch bin/true $files 2>/dev/null | docker import - course-docker-trial >/dev/null 2>&1 \
        && docker run --rm --network none course-docker-trial /bin/true >/dev/null 2>&1
}

course_docker_engine() {
    _course_docker_tools
    if [ -z "${DOCKER_HOST:-}" ]; then
        mkdir -p "$COURSE_DOCKER_ROOT"
        export DOCKER_HOST="unix://$COURSE_DOCKER_ROOT/docker.sock"
    fi
    docker version >/dev/null 2>&1 && return 0
    # overlay2 is the quick one, but it cannot work on every file system (overlayfs inside a
    # container, for one): a container that does not start there means vfs, slower but anywhere.
    if _course_dockerd_start overlay2 && _course_docker_trial_run; then return 0; fi
    course_docker_stop
    echo "docker: overlay2 does not work here (log: $COURSE_DOCKER_ROOT/dockerd-overlay2.log); using vfs" >&2
    _course_dockerd_start vfs && _course_docker_trial_run && return 0
    tail -n 20 "$COURSE_DOCKER_ROOT/dockerd-vfs.log" >&2
    echo "docker: dockerd did not start (log: $COURSE_DOCKER_ROOT/dockerd-vfs.log)" >&2
    return 1
}

# "URI SUITE COMPONENTS..." for every deb source of this machine's apt, one-line and deb822 files alike.
_course_apt_sources() {
    local list=(/etc/apt/sources.list /etc/apt/sources.list.d/*.list) deb822=(/etc/apt/sources.list.d/*.sources)
    awk '$1 == "deb" { sub(/^deb[ \t]+(\[[^]]*\][ \t]+)?/, ""); print }' "${list[@]}" 2>/dev/null || true
    awk 'function flush(   u, s, nu, ns, i, j) {
             if (types ~ /(^| )deb( |$)/ && enabled !~ /^no$/) {
                 nu = split(uris, u, " "); ns = split(suites, s, " ")
                 for (i = 1; i <= nu; i++) for (j = 1; j <= ns; j++) print u[i], s[j], comps
             }
             types = uris = suites = comps = ""; enabled = "yes"
         }
         BEGIN { enabled = "yes" }
         /^[ \t]*#/ { next }
         /^[ \t]*$/ { flush(); next }
         /^Types:/ { sub(/^Types:[ \t]*/, ""); types = $0 }
         /^URIs:/ { sub(/^URIs:[ \t]*/, ""); uris = $0 }
         /^Suites:/ { sub(/^Suites:[ \t]*/, ""); suites = $0 }
         /^Components:/ { sub(/^Components:[ \t]*/, ""); comps = $0 }
         /^Enabled:/ { sub(/^Enabled:[ \t]*/, ""); enabled = $0 }
         END { flush() }' "${deb822[@]}" 2>/dev/null || true
}

# The URI this machine's apt uses for the Debian suite whose name ends in $1 ("" for the main suite,
# "-security", "-updates"): the host's own suite first, then any suite the course supports.
_course_apt_uri() {
    local codename suite
    codename=$(sed -n 's/^VERSION_CODENAME=//p' /etc/os-release 2>/dev/null | tr -d '"')
    for suite in $codename bookworm trixie; do
        _course_apt_sources | awk -v s="$suite$1" '$2 == s && / main( |$)/ { print $1; exit }' | grep . && return 0
    done
    return 1
}

# The proxy apt uses for http, if any.
_course_apt_proxy() {
    apt-config dump Acquire::http::Proxy 2>/dev/null | sed -n 's/^Acquire::http::Proxy "\(.*\)";$/\1/p' | head -n1
}

# Makes the debian:SUITE base image from the archive this machine's apt uses; the image's apt uses
# that archive too, with the suite's updates and security archives where this machine has them.
_course_docker_base_image() {
    local suite=$1 mirror security proxy rootfs="$COURSE_DOCKER_ROOT/rootfs-$1"
    mirror=$(_course_apt_uri "") || { echo "docker: this machine's apt has no Debian main archive to make debian:$suite from" >&2; return 1; }
    security=$(_course_apt_uri -security) || security=""
    proxy=$(_course_apt_proxy)
    echo "docker: making the debian:$suite base image with debootstrap (this machine's archive${proxy:+ and proxy})" >&2
    rm -rf "$rootfs"
    http_proxy="${proxy:-${http_proxy:-}}" debootstrap --variant=minbase "$suite" "$rootfs" "$mirror" \
        > "$COURSE_DOCKER_ROOT/debootstrap-$suite.log" 2>&1 \
        || { tail -n 20 "$COURSE_DOCKER_ROOT/debootstrap-$suite.log" >&2; return 1; }
    {
        echo "deb $mirror $suite main"
        _course_apt_uri -updates >/dev/null && echo "deb $mirror $suite-updates main"
        [ -n "$security" ] && echo "deb $security $suite-security main"
    } > "$rootfs/etc/apt/sources.list"
    tar -C "$rootfs" -c . | docker import - "debian:$suite" >/dev/null
    rm -rf "$rootfs"
}

course_docker_image() {
    _course_docker_build "${1:-trixie}" "${COURSE_IMAGE_NAME:-ros-course}:${1:-trixie}" ""
}

# The grading image's name: the course image's, ending in -grader (the only place it is made).
course_docker_grading_image() {
    _course_docker_build "${1:-trixie}" "${COURSE_IMAGE_NAME:-ros-course}-grader:${1:-trixie}" grader
}

# Builds the target $3 of docker/Dockerfile (its last, the students' image, when "") for suite $1 as
# image $2, and prints $2.
_course_docker_build() {
    local suite=$1 image=$2 target=$3 proxy log
    log="$COURSE_DOCKER_ROOT/build-${target:+$target-}$suite.log"
    if ! docker image inspect "debian:$suite" >/dev/null 2>&1; then
        _course_docker_base_image "$suite" || return 1
    fi
    proxy=$(_course_apt_proxy)
    echo "docker: building $image" >&2
    # http_proxy is one of Docker's own build arguments: apt in the build uses it, the image keeps none.
    docker build --network host --build-arg "SUITE=$suite" ${proxy:+--build-arg "http_proxy=$proxy"} \
        ${target:+--target "$target"} -t "$image" -f "$_course_docker_top/docker/Dockerfile" \
        "$_course_docker_top" > "$log" 2>&1 \
        || { tail -n 40 "$log" >&2; echo "docker: docker build failed" >&2; return 1; }
    echo "$image"
}
