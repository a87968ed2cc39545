#!/usr/bin/env bash
# Runs every test of the workspace: ./test.sh        (or only some packages: ./test.sh turtlesim my_turtle)
# Installs what is missing, builds, then runs the steps: the pure tests (a pytest per folder), the
# workspace's pytests and the rostests, two (up to six, while the cores are idle) at a time, the ones
# that measure rates first, one at a time, with the others beside them at a lower CPU priority, and
# ends with one line `N passed, N failed` (docs/testing.md).
# Exit status 0 only if every step found its tests, ran them, and they all passed.
# Environment: TEST_JOBS  how many slow steps run side by side (default auto: 2, and more while the
#                         cores are idle enough for the next; 1 = one after the other)
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"

# The packages of this workspace (name and folder), read from their package.xml files: on a fresh
# machine catkin is not installed yet, and this list must not depend on it.
declare -A package_dirs=()
while IFS= read -r xml; do
    dir=$(dirname "$xml")
    ignored=no
    for parent in "$dir" "$(dirname "$dir")"; do
        [ -e "$parent/CATKIN_IGNORE" ] && ignored=yes
    done
    [ "$ignored" = yes ] && continue
    name=$(sed -n 's:.*<name>[[:space:]]*\([^<[:space:]]*\)[[:space:]]*</name>.*:\1:p' "$xml" | head -n1)
    [ -n "$name" ] && package_dirs[$name]=$dir
done < <(find "$ROOT/src" -mindepth 2 -maxdepth 3 -name package.xml | sort)
mapfile -t all_packages < <(printf '%s\n' "${!package_dirs[@]}" | sort)
if [ ${#package_dirs[@]} -eq 0 ]; then
    echo "test: found no package (no src/*/package.xml nor src/*/*/package.xml): nothing to test" >&2
    exit 1
fi

if [ $# -gt 0 ]; then
    packages=("$@")
    for pkg in "${packages[@]}"; do
        [ -n "${package_dirs[$pkg]:-}" ] || {
            echo "test: no package named $pkg here; the packages are:" "${all_packages[@]}" >&2
            exit 2; }
    done
else
    packages=("${all_packages[@]}")
fi
"$ROOT/tools/setup.sh" || exit 1
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"

BASE="${CATKIN_BUILD_BASE:-$ROOT}"
RESULTS="$BASE/build/test_results"
LOGS="$BASE/build/test_logs"
rm -rf "$RESULTS" "$LOGS"
mkdir -p "$RESULTS/pytest" "$LOGS"
export DISPLAY=   # the tests start their own Xvfb where they need a screen
# The steps' ROS home: their logs, rostest's pid files, the checks they run and their pictures
# (course_testing.pictures) stay with this run's logs, not in the user's ~/.ros.
export ROS_HOME="$LOGS/ros_home"
# And a home of their own: what the programs they start keep there (rviz's ~/.rviz, Mesa's shader
# cache, chromium's profile) stays with this run's logs too, not in the user's home.
export HOME="$LOGS/home"
mkdir -p "$HOME"

step_failures=()
expected=()   # result files the steps must write, each with at least one test case
PYTEST=(/usr/bin/python3 -m pytest -q -p no:cacheprovider)

jobs_file="$LOGS/jobs.txt"
: > "$jobs_file"
# Steps that measure wall-clock rates and run alone (the file says why), by label.
ALONE=()
[ -f "$ROOT/tools/test-alone-steps.txt" ] && mapfile -t ALONE < <(sed -e '/^#/d' -e '/^[[:space:]]*$/d' "$ROOT/tools/test-alone-steps.txt")
# add_job LABEL EXIT_CODES COMMAND...: one line of run_test_jobs.py's list (EXIT_CODES: the statuses
# after which the command's result file tells the rest).
add_job() {
    local sharing=shared
    local step
    for step in "${ALONE[@]}"; do [ "$step" = "$1" ] && sharing=alone; done
    { printf '%s\t%s\t%s\t' "$1" "$2" "$sharing"; shift 2; printf '%q ' "$@"; echo; } >> "$jobs_file"
}

# 1. Pure tests: no master, milliseconds each. One pytest per folder, so that test modules of the
#    same name in two packages (test_world.py) do not meet. Steps like the others below (pytest's
#    exit 5: it collected no tests), so that they run beside them.
for pkg in "${packages[@]}"; do
    dir="${package_dirs[$pkg]}/test/unit"
    [ -d "$dir" ] || continue
    add_job "pytest ${dir#"$ROOT"/}" 0,1 "${PYTEST[@]}" --junitxml="$RESULTS/pytest/$pkg.xml" "$dir"
    expected+=(pytest/$pkg.xml)
done

# The workspace's own tests (tests/), when no package is named: the quick ones in one step, the
# slow ones (minutes each) a step each; each test file of a folder in SPLIT_WORKSPACE_TESTS is a
# step of its own (tests/student/: a student per file, one lab each; tests/network/: the files
# that measure rates and latencies apart from the others).
SLOW_WORKSPACE_TESTS=(network student test_tour.py)
SPLIT_WORKSPACE_TESTS=(network student)
# Files of tests/ that need root, run where the tests run as root (CI's host side), not as an
# ordinary user (the Docker image's, a student's): two network namespaces need CAP_NET_ADMIN, a
# second user's processes need root to start and to be killed. Elsewhere a line says they did not run.
ROOT_ONLY_WORKSPACE_TESTS=(network/test_two_hosts.py test_user_reaper.py)
root_only() {
    local file
    [ "$(id -u)" = 0 ] && return 1
    for file in "${ROOT_ONLY_WORKSPACE_TESTS[@]}"; do [ "$1" = "$file" ] && return 0; done
    return 1
}
if [ $# -eq 0 ] && [ -d "$ROOT/tests" ]; then
    args=()
    for part in "${SLOW_WORKSPACE_TESTS[@]}"; do args+=(--ignore="$ROOT/tests/$part"); done
    for part in "${ROOT_ONLY_WORKSPACE_TESTS[@]}"; do
        # Those at the top of tests/ (the quick step's); the others are steps of their own, below.
        if root_only "$part" && [ -e "$ROOT/tests/$part" ] && [ "$part" = "${part##*/}" ]; then
            echo "test: tests/$part needs root: not run here"
            args+=(--ignore="$ROOT/tests/$part")
        fi
    done
    add_job "pytest tests" 0,1 "${PYTEST[@]}" --junitxml="$RESULTS/pytest/workspace.xml" "${args[@]}" "$ROOT/tests"
    expected+=(pytest/workspace.xml)
fi

# 2. The slow steps: every registered rostest (each starts its own master on a free port) and, when
#    no package is named, the workspace's slow tests in tests/.
if [ $# -eq 0 ]; then
    steps=()
    for part in "${SLOW_WORKSPACE_TESTS[@]}"; do
        [ -e "$ROOT/tests/$part" ] || continue
        split=no
        for folder in "${SPLIT_WORKSPACE_TESTS[@]}"; do [ "$part" = "$folder" ] && split=yes; done
        if [ "$split" = yes ]; then
            for file in "$ROOT/tests/$part"/test_*.py; do [ -e "$file" ] && steps+=("$part/${file##*/}"); done
        else
            steps+=("$part")
        fi
    done
    for part in "${steps[@]}"; do
        if root_only "$part"; then
            echo "test: tests/$part needs root: not run here"
            continue
        fi
        name="workspace-$(echo "${part%.py}" | tr / -)"
        # Their temporary folders (the tour's pictures and logs) are kept beside the step's log.
        add_job "pytest tests/$part" 0,1 "${PYTEST[@]}" --junitxml="$RESULTS/pytest/$name.xml" \
            --basetemp="$LOGS/$name" "$ROOT/tests/$part"
        expected+=(pytest/$name.xml)
    done
fi
for pkg in "${packages[@]}"; do
    dir="${package_dirs[$pkg]}"
    # add_rostest(test/name.test): the files catkin registers, as catkin's run_tests target runs them.
    while IFS= read -r file; do
        [ -n "$file" ] || continue
        result=$(echo "${file%.test}" | tr / _)
        add_job "rostest ${dir#"$ROOT"/src/}/$file" 0,1,2 rostest --pkgdir="$dir" --package="$pkg" \
            --results-filename "$result.xml" --results-base-dir "$RESULTS" "$dir/$file"
        expected+=("$pkg/rostest-$result.xml")
    done < <(sed -n 's/^[^#]*add_rostest([[:space:]]*\([^[:space:])]*\).*/\1/p' "$dir/CMakeLists.txt" 2>/dev/null)
done

# A step of ALONE that is not among the steps (renamed, moved) would run beside others unseen: on a
# whole run, each must name a step (one that needs root is left out where the tests run without it).
if [ $# -eq 0 ]; then
    declare -A labels=()
    while IFS=$'\t' read -r label _; do labels["$label"]=1; done < "$jobs_file"
    for step in "${ALONE[@]}"; do
        if [ -z "${labels[$step]:-}" ] && ! root_only "${step#pytest tests/}"; then
            step_failures+=("tools/test-alone-steps.txt names '$step', which is no step of this run")
        fi
    done
fi

if [ -s "$jobs_file" ]; then
    echo "test: building the tests"
    if ! "$ROOT/tools/setup.sh" --make tests -j2 > "$LOGS/test_build.log" 2>&1; then
        tail -n 40 "$LOGS/test_build.log"; step_failures+=("building the tests (log $LOGS/test_build.log)")
    fi
    echo "test: $(wc -l < "$jobs_file") steps (pytest folders and files, rostests), ${TEST_JOBS:-2 to 6} at a time (logs in ${LOGS#"$ROOT"/})"
    /usr/bin/python3 "$ROOT/tools/run_test_jobs.py" --jobs "${TEST_JOBS:-auto}" --logs "$LOGS" \
        --times "$BASE/build/test_durations.txt" --first-times "$ROOT/tools/test-step-seconds.txt" \
        --failed-steps "$LOGS/failed_steps.txt" < "$jobs_file" \
        || step_failures+=("running the slow steps")
    [ -f "$LOGS/failed_steps.txt" ] && mapfile -t -O ${#step_failures[@]} step_failures < "$LOGS/failed_steps.txt"
fi

# 3. One count over everything that ran, and over what should have run but left no results.
expect_args=()
for file in "${expected[@]}"; do expect_args+=(--expect "$file"); done
/usr/bin/python3 "$ROOT/tools/count_results.py" "$RESULTS" "${expect_args[@]}" "${step_failures[@]}"
