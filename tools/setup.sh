#!/usr/bin/env bash
# Installs the Debian packages the workspace needs (only the missing ones) and builds it.
#
# Idempotent: with everything installed and nothing changed it only re-runs catkin_make (a few seconds).
# Usage: tools/setup.sh                  install what is missing, then build
#        tools/setup.sh --install-only   only install
#        tools/setup.sh --make TARGET... catkin_make of those targets (tests, run_tests, ...) in the
#                                        same build, output to stdout (for test.sh)
# Environment:
#   CATKIN_BUILD_BASE   folder that receives build/ and devel/ (default: the repository root)
#   CATKIN_WHITELIST    ';'-separated packages to build (default: all of them)
#   COURSE_SKIP_INSTALL=1  do not look at Debian packages at all
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"   # Debian's python3 (with rospy) before any pyenv

missing_packages() {
    local wanted
    wanted=$(grep -v -e '^#' -e '^[[:space:]]*$' "$ROOT/tools/debian-packages.txt")
    for pkg in $wanted; do
        dpkg-query -W -f='${Status}\n' "$pkg" 2>/dev/null | grep -q "install ok installed" || echo "$pkg"
    done
}

install_missing() {
    local missing
    missing=$(missing_packages)
    [ -z "$missing" ] && return 0
    echo "setup: installing Debian packages:" $missing
    local sudo=""
    if [ "$(id -u)" != 0 ]; then
        command -v sudo >/dev/null || { echo "setup: these packages are missing and I am not root (no sudo either): $missing" >&2; exit 1; }
        sudo="sudo"
    fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $missing
}

BASE="${CATKIN_BUILD_BASE:-$ROOT}"
workspace_make() {
    catkin_make --directory "$ROOT" --build "$BASE/build" \
        -DCATKIN_DEVEL_PREFIX="$BASE/devel" -DCMAKE_INSTALL_PREFIX="$BASE/install" \
        -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
        -DCATKIN_WHITELIST_PACKAGES="${CATKIN_WHITELIST:-}" "$@"
}

if [ "${1:-}" = --make ]; then
    shift
    workspace_make "$@"
    exit
fi
[ "${COURSE_SKIP_INSTALL:-0}" = 1 ] || install_missing
[ "${1:-}" = --install-only ] && exit 0
mkdir -p "$BASE"
echo "setup: building the workspace (catkin_make) into $BASE"
if ! workspace_make -j2 > "$BASE/catkin_make.log" 2>&1; then
    tail -n 60 "$BASE/catkin_make.log" >&2
    echo "setup: catkin_make failed; the whole log is $BASE/catkin_make.log" >&2
    exit 1
fi
