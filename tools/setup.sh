#!/usr/bin/env bash
# Installs the Debian packages the workspace needs (only the missing ones) and builds it.
#
# Idempotent: with everything installed and nothing changed it only re-runs catkin_make (a few seconds).
# Usage: tools/setup.sh                  install what is missing, then build
#        tools/setup.sh --install-only   only install
#        tools/setup.sh --install-only --grading
#                                        only install what a grading needs (the grading image,
#                                        docker/Dockerfile's target grader); --grading goes with
#                                        --install-only, --check and --packages
#        tools/setup.sh --check          say whether this machine can take the course; installs nothing
#        tools/setup.sh --packages       print the package list for this machine's Debian suite
#        tools/setup.sh --make TARGET... catkin_make of those targets (tests, run_tests, ...) in the
#                                        same build, output to stdout (for test.sh)
# Environment:
#   CATKIN_BUILD_BASE   folder that receives build/ and devel/ (default: the repository root)
#   CATKIN_WHITELIST    ';'-separated packages to build (default: all of them)
#   COURSE_SKIP_INSTALL=1  do not look at Debian packages at all
#   COURSE_OS_RELEASE   os-release file that names the system (default /etc/os-release)
#   COURSE_PACKAGE_LIST package list (default tools/debian-packages.txt)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"   # Debian's python3 (with rospy) before any pyenv

# The Debian suites whose own archive carries every package of the list (ROS 1 included).
SUPPORTED_SUITES="trixie bookworm"
OS_RELEASE="${COURSE_OS_RELEASE:-/etc/os-release}"
PACKAGE_LIST="${COURSE_PACKAGE_LIST:-$ROOT/tools/debian-packages.txt}"
REFUSED=3   # exit status when this machine cannot take the course; nothing was installed
DOCKER_WAY_OUT="use the Docker image instead (docs/student-docker.md)"

# One field of os-release (shell-style KEY=value, value maybe quoted), empty when absent.
os_release_field() {
    [ -r "$OS_RELEASE" ] || return 0
    sed -n "s/^$1=//p" "$OS_RELEASE" | head -n1 | sed -e 's/^"\(.*\)"$/\1/' -e "s/^'\(.*\)'$/\1/"
}

# Prints the Debian suite of this machine, or says in one sentence why it cannot take the course.
debian_suite() {
    local id codename name suite
    id=$(os_release_field ID)
    codename=$(os_release_field VERSION_CODENAME)
    name=$(os_release_field PRETTY_NAME)
    name="${name:-an unknown system (no $OS_RELEASE)}"
    for suite in $SUPPORTED_SUITES; do
        if [ "$id" = debian ] && [ "$codename" = "$suite" ]; then echo "$suite"; return 0; fi
    done
    echo "setup: this machine runs $name, but the course installs only on Debian 13 trixie or" \
         "Debian 12 bookworm (whose own archive carries ROS 1), so nothing was installed: $DOCKER_WAY_OUT." >&2
    return $REFUSED
}

# The package list for SUITE: plain lines for every suite, `SUITE: package` lines for that suite only.
# PART: all (default), build (the lines above the first `# ----` line: what catkin_make needs) or
# later (the lines below it). With GRADING=1, only the lines above the `# ====` line (what a grading
# needs).
GRADING=0
suite_packages() {
    local suite=$1 part=${2:-all} line section=build
    while IFS= read -r line || [ -n "$line" ]; do
        case "$line" in
            "# ----"*) section=later ;;
            "# ===="*) [ "$GRADING" = 1 ] && break ;;
        esac
        [ "$part" = all ] || [ "$part" = "$section" ] || continue
        line="${line%%#*}"
        line="$(echo "$line" | xargs)"
        [ -z "$line" ] && continue
        case "$line" in
            *:*) [ "${line%%:*}" = "$suite" ] && echo "${line#*:}" | xargs ;;
            *) echo "$line" ;;
        esac
    done < "$PACKAGE_LIST"
}

# Those of the packages named that are not installed (one dpkg-query for all of them).
missing_packages() {
    [ $# -gt 0 ] || return 0
    local installed pkg
    installed=" $(dpkg-query -W -f='${Status} ${Package}\n' "$@" 2>/dev/null \
                  | sed -n 's/^install ok installed //p' | tr '\n' ' ')"
    for pkg in "$@"; do
        case "$installed" in *" $pkg "*) ;; *) echo "$pkg" ;; esac
    done
}

# Those of the packages named that apt has no candidate for, with apt's lists as they are now (one
# apt-cache call for all of them; it prints a block `name:` ... `  Candidate: version` for each
# package it knows).
unavailable_packages() {
    [ $# -gt 0 ] || return 0
    local available pkg
    available=" $(apt-cache policy "$@" 2>/dev/null \
                  | awk '/^[^ ]/ { name = $1; sub(/:$/, "", name) }
                         /^ +Candidate:/ && $2 != "(none)" { print name }' | tr '\n' ' ')"
    for pkg in "$@"; do
        case "$available" in *" $pkg "*) ;; *) echo "$pkg" ;; esac
    done
}

refuse_unavailable() {
    echo "setup: this Debian $1 has no package named $(echo $2) in its apt sources, so nothing was" \
         "installed: enable the suite's main archive in apt, or $DOCKER_WAY_OUT." >&2
    exit $REFUSED
}

SUITE=""
SUDO=()
LATER_PACKAGES=""   # missing packages that catkin_make does not need, left for install_later
# Checks that apt has every missing package, then installs the ones catkin_make needs.
install_missing() {
    local missing unavailable
    SUITE=$(debian_suite) || exit $REFUSED
    missing=$(missing_packages $(suite_packages "$SUITE"))
    [ -z "$missing" ] && return 0
    if [ "$(id -u)" != 0 ]; then
        command -v sudo >/dev/null || { echo "setup: these packages are missing and I am not root (no sudo either):" $missing >&2; exit 1; }
        SUDO=(sudo)
    fi
    "${SUDO[@]}" apt-get update -qq
    # Every package available before any is installed: never a half-installed machine.
    unavailable=$(unavailable_packages $missing)
    [ -z "$unavailable" ] || refuse_unavailable "$SUITE" "$unavailable"
    LATER_PACKAGES=$(missing_packages $(suite_packages "$SUITE" later))
    apt_install $(missing_packages $(suite_packages "$SUITE" build))
}

install_later() {
    apt_install $LATER_PACKAGES
}

apt_install() {
    [ $# -gt 0 ] || return 0
    echo "setup: installing Debian $SUITE packages:" "$@"
    # sudo resets the environment, so the variable goes on its command line. dpkg unpacks without
    # syncing each file to disk (--force-unsafe-io): only packages that were missing are unpacked, so a
    # machine that loses power mid-install loses none of what it had, and reinstalling those packages
    # (apt-get install --reinstall) repairs it.
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
        -o Dpkg::Options::=--force-unsafe-io "$@"
}

BASE="${CATKIN_BUILD_BASE:-$ROOT}"
# One catkin_make at a time in a build folder: two commands of this checkout at once (two ./grade.sh,
# ./grade.sh beside ./test.sh) would otherwise break each other's build; the second waits.
workspace_make() {
    mkdir -p "$BASE/build"
    flock "$BASE/build/.catkin_make.lock" catkin_make --directory "$ROOT" --build "$BASE/build" \
        -DCATKIN_DEVEL_PREFIX="$BASE/devel" -DCMAKE_INSTALL_PREFIX="$BASE/install" \
        -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
        -DCATKIN_WHITELIST_PACKAGES="${CATKIN_WHITELIST:-}" "$@"
}

# --grading, after the command's own option: the grading image's packages only.
if [ "${2:-}" = --grading ]; then
    case "${1:-}" in
        --install-only|--check|--packages) GRADING=1; set -- "$1" ;;
        *) echo "setup: --grading goes after --install-only, --check or --packages" >&2; exit 2 ;;
    esac
fi
case "${1:-}" in
    --make)
        shift
        workspace_make "$@"
        exit ;;
    --packages)
        suite=$(debian_suite) || exit $REFUSED
        suite_packages "$suite"
        exit 0 ;;
    --check)
        suite=$(debian_suite) || exit $REFUSED
        packages=$(suite_packages "$suite")
        unavailable=$(unavailable_packages $(missing_packages $packages))
        [ -z "$unavailable" ] || refuse_unavailable "$suite" "$unavailable"
        echo "setup: Debian $suite: every package of the course is installed or available"
        exit 0 ;;
esac
[ "${COURSE_SKIP_INSTALL:-0}" = 1 ] || install_missing
if [ "${1:-}" = --install-only ]; then
    install_later
    exit 0
fi
mkdir -p "$BASE"
echo "setup: building the workspace (catkin_make) into $BASE"
# The packages catkin_make does not need install meanwhile (apt in the foreground, where sudo can
# ask for a password); a failed install waits for the build to end, so that nothing is left running.
workspace_make -j2 > "$BASE/catkin_make.log" 2>&1 &
make_pid=$!
installed=yes
install_later || installed=no
if ! wait $make_pid; then
    tail -n 60 "$BASE/catkin_make.log" >&2
    echo "setup: catkin_make failed; the whole log is $BASE/catkin_make.log" >&2
    exit 1
fi
[ "$installed" = yes ] || { echo "setup: apt-get install failed (above)" >&2; exit 1; }
# The course's Python compiled once: where nothing writes bytecode (PYTHONDONTWRITEBYTECODE, a
# read-only tree: a grading's sandbox) every process would compile its modules again at its start
# (20 - 70 ms of CPU for a simulator, a grading or a test node). An unchanged module is not compiled again.
(cd "$ROOT" && /usr/bin/python3 -m compileall -q src/*/src src/compat/*/src "$BASE/devel/lib/python3") \
    || { echo "setup: compiling the course's Python failed" >&2; exit 1; }
