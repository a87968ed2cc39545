# Sourced by the project's scripts (and by you: `source tools/env.sh`) after tools/setup.sh has built
# the workspace. It sources devel/setup.bash, whose environment hooks (course_environment,
# ros_loopback) give every shell that sources it, or an overlay's, Debian's python3 first and ROS
# sockets on loopback. This file only adds the care a script needs.
# devel/setup.bash reads unset variables (callers running with `set -u` must not abort in it) and
# hands its arguments to catkin: sourced from a function, it sees none of the caller's (./demo.sh --help).
_course_source_devel() {
    local nounset devel
    nounset=$(set -o | awk '$1 == "nounset" {print $2}')
    devel="${CATKIN_BUILD_BASE:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}/devel"
    set +u
    # shellcheck disable=SC1091
    source "$devel/setup.bash"
    [ "$nounset" = on ] && set -u
    return 0
}
_course_source_devel
unset -f _course_source_devel
