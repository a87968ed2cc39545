#!/usr/bin/env bash
# Makes a student's own catkin workspace on top of this one (an overlay), as the slides' ~/catkin_ws:
#   tools/new-workspace.sh ~/catkin_ws
# Then, in every new terminal:  source ~/catkin_ws/devel/setup.bash
# That one line gives this workspace's packages (turtlesim, turtlebot3_gazebo, ...) and environment
# (Debian's python3 first, ROS on loopback) plus the student's own packages. docs/student-workspace.md
# says more, and what happens when a package of yours has the name of one of ours (shadowing).
set -euo pipefail

usage() { echo "usage: $0 DIR   (a new or empty folder, or a workspace made by this script)" >&2; exit 2; }
[ $# -eq 1 ] && [ -n "$1" ] || usage
case "$1" in -*) usage ;; esac

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
UNDERLAY="${CATKIN_BUILD_BASE:-$ROOT}/devel"
if [ ! -f "$UNDERLAY/setup.bash" ]; then
    echo "new-workspace: $UNDERLAY/setup.bash is missing: build this workspace first (tools/setup.sh)" >&2
    exit 1
fi
WORKSPACE="$1"
if [ -e "$WORKSPACE" ] && [ ! -d "$WORKSPACE" ]; then
    echo "new-workspace: $WORKSPACE exists and is not a folder" >&2
    exit 1
fi
if [ -d "$WORKSPACE" ] && [ -n "$(ls -A "$WORKSPACE")" ] && [ ! -d "$WORKSPACE/src" ]; then
    echo "new-workspace: $WORKSPACE is not empty and has no src/: give a new or empty folder" >&2
    exit 1
fi
WORKSPACE="$(mkdir -p "$WORKSPACE/src" && cd "$WORKSPACE" && pwd)"
if [ "$WORKSPACE" = "$ROOT" ]; then
    echo "new-workspace: that is this workspace itself; give another folder" >&2
    exit 1
fi

# The underlay's environment while catkin_make records it: the new devel/setup.bash will then source
# this workspace (and its environment hooks) first.
# shellcheck disable=SC1091
set +u; source "$UNDERLAY/setup.bash"; set -u
cd "$WORKSPACE"
if ! catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 > "$WORKSPACE/catkin_make.log" 2>&1; then
    tail -n 30 "$WORKSPACE/catkin_make.log" >&2
    echo "new-workspace: catkin_make failed; the whole log is $WORKSPACE/catkin_make.log" >&2
    exit 1
fi
cat <<EOT
Made the workspace $WORKSPACE on top of $UNDERLAY.
In every new terminal (or once in ~/.bashrc):
    source $WORKSPACE/devel/setup.bash
Your packages go in $WORKSPACE/src (cd $WORKSPACE/src && catkin_create_pkg ...), then: cd $WORKSPACE && catkin_make
EOT
