# Sourced by the project's scripts (and by you: `source tools/env.sh`) after tools/setup.sh has built
# the workspace: ROS environment of the devel space, Debian's python3 first, ROS sockets on loopback.
_course_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
# devel/setup.bash reads unset variables (callers running with `set -u` must not abort in it) and
# hands its arguments to catkin: sourced from a function, it sees none of the caller's (./demo.sh --help).
_course_source_devel() {
    local nounset
    nounset=$(set -o | awk '$1 == "nounset" {print $2}')
    set +u
    # shellcheck disable=SC1091
    source "${CATKIN_BUILD_BASE:-$_course_root}/devel/setup.bash"
    [ "$nounset" = on ] && set -u
    return 0
}
_course_source_devel
# By default nothing is reachable from other machines: master and nodes listen on loopback.
# For two machines set ROS_MASTER_URI and ROS_IP yourself (README: "Two machines"); ROS_IP then
# wins over the ROS_HOSTNAME=localhost that an earlier sourcing of this file left in the shell.
if [ -z "${ROS_IP:-}" ]; then
    export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
elif [ "${ROS_HOSTNAME:-}" = localhost ]; then
    unset ROS_HOSTNAME
fi
# roscpp's XML-RPC server (every C++ node, rosout) binds 0.0.0.0 whatever ROS_HOSTNAME says:
# ros_loopback moves such binds to loopback while the ROS address is a loopback one, and does
# nothing when ROS_IP or ROS_HOSTNAME names a real address (two machines).
_course_loopback="${CATKIN_BUILD_BASE:-$_course_root}/devel/lib/libros_loopback.so"
if [ -f "$_course_loopback" ]; then
    case ":${LD_PRELOAD:-}:" in
        *":$_course_loopback:"*) ;;
        *) export LD_PRELOAD="$_course_loopback${LD_PRELOAD:+:$LD_PRELOAD}" ;;
    esac
fi
export ROS_MASTER_URI="${ROS_MASTER_URI:-http://localhost:11311}"
export PYTHONNOUSERSITE=1
unset -f _course_source_devel
unset _course_root _course_loopback
