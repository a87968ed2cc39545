# Sourced by the project's scripts (and by you: `source tools/env.sh`) after tools/setup.sh has built
# the workspace: ROS environment of the devel space, Debian's python3 first, ROS sockets on loopback.
_course_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
# shellcheck disable=SC1091
source "${CATKIN_BUILD_BASE:-$_course_root}/devel/setup.bash"
# By default nothing is reachable from other machines: master and nodes listen on loopback.
# For two machines set ROS_MASTER_URI and ROS_IP yourself (README: "Two machines").
if [ -z "${ROS_IP:-}" ]; then
    export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
fi
export ROS_MASTER_URI="${ROS_MASTER_URI:-http://localhost:11311}"
export PYTHONNOUSERSITE=1
unset _course_root
