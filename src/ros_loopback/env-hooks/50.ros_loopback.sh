# Sourced by setup.sh/setup.bash of this workspace and of every workspace built on top of it:
# by default ROS listens on loopback only, as tools/env.sh always did.
#
# Without ROS_IP, the node address is ROS_HOSTNAME=localhost (unless ROS_HOSTNAME is set), and
# libros_loopback.so is preloaded: roscpp's XML-RPC server (every C++ node, rosout) binds 0.0.0.0
# whatever ROS_HOSTNAME says, and the library moves that bind to loopback. A real ROS_IP or
# ROS_HOSTNAME (two machines) turns both off; a ROS_HOSTNAME=localhost left by an earlier sourcing
# then gives way to ROS_IP. POSIX sh: setup.sh sources this file from sh, bash and zsh.
if [ -z "${ROS_IP:-}" ]; then
    ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
    export ROS_HOSTNAME
elif [ "${ROS_HOSTNAME:-}" = localhost ]; then
    unset ROS_HOSTNAME
fi

# The address nodes advertise: ROS_HOSTNAME wins over ROS_IP, as in roscpp and rospy.
case "${ROS_HOSTNAME:-${ROS_IP:-}}" in
    localhost | 127.* | ::1) _ros_loopback_wanted=1 ;;
    *) _ros_loopback_wanted=0 ;;
esac
# CATKIN_ENV_HOOK_WORKSPACE is the devel or install space that holds this hook, wherever it was
# built (CATKIN_BUILD_BASE) or installed: the library sits in its lib/ in both.
_ros_loopback_library="${CATKIN_ENV_HOOK_WORKSPACE:-}/lib/libros_loopback.so"
# LD_PRELOAD without any libros_loopback.so (this one or another workspace's), then with this one
# in front when wanted and present: sourcing twice, or another workspace's setup, adds no copy.
_ros_loopback_others=
_ros_loopback_rest="${LD_PRELOAD:-}"
while [ -n "$_ros_loopback_rest" ]; do
    _ros_loopback_entry="${_ros_loopback_rest%%:*}"
    case "$_ros_loopback_rest" in
        *:*) _ros_loopback_rest="${_ros_loopback_rest#*:}" ;;
        *) _ros_loopback_rest= ;;
    esac
    case "$_ros_loopback_entry" in
        '' | */libros_loopback.so) ;;
        *) _ros_loopback_others="${_ros_loopback_others:+$_ros_loopback_others:}$_ros_loopback_entry" ;;
    esac
done
if [ "$_ros_loopback_wanted" = 1 ] && [ -f "$_ros_loopback_library" ]; then
    _ros_loopback_others="$_ros_loopback_library${_ros_loopback_others:+:$_ros_loopback_others}"
fi
if [ -n "$_ros_loopback_others" ]; then
    LD_PRELOAD="$_ros_loopback_others"
    export LD_PRELOAD
else
    unset LD_PRELOAD
fi
unset _ros_loopback_wanted _ros_loopback_library _ros_loopback_others _ros_loopback_rest \
    _ros_loopback_entry
