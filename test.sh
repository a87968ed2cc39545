#!/usr/bin/env bash
# Runs every test of the workspace: ./test.sh        (or only some packages: ./test.sh turtlesim my_turtle)
# Installs what is missing, builds, runs the pure tests (pytest), then the rostests and the workspace's
# slow pytests two (or three, on a quiet machine) at a time, and ends with one line `N passed, N failed`
# (docs/testing.md).
# Exit status 0 only if every step found its tests, ran them, and they all passed.
# Environment: TEST_JOBS  how many slow steps run side by side (default auto: 2, and a third while a
#                         core is idle; 1 = one after the other)
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

step_failures=()
expected=()   # result files the steps must write, each with at least one test case
PYTEST=(/usr/bin/python3 -m pytest -q -p no:cacheprovider)

# pytest's exit status: 0 passed, 1 some failed (both counted from the result file); anything else
# means it did not run its tests, 5 that it found none.
pytest_failure() {
    case "$2" in
        0|1) return 1 ;;
        5) echo "pytest $1 collected no tests (exit 5)" ;;
        *) echo "pytest $1 could not run its tests (exit $2)" ;;
    esac
}

# 1. Pure tests: no master, milliseconds each. One pytest per folder, so that test modules of the
#    same name in two packages (test_world.py) do not meet.
for pkg in "${packages[@]}"; do
    dir="${package_dirs[$pkg]}/test/unit"
    [ -d "$dir" ] || continue
    echo "test: pytest ${dir#"$ROOT"/}"
    "${PYTEST[@]}" --junitxml="$RESULTS/pytest/$pkg.xml" "$dir" | tail -n 1
    why=$(pytest_failure "${dir#"$ROOT"/}" "${PIPESTATUS[0]}") && step_failures+=("$why")
    expected+=(pytest/$pkg.xml)
done

# The workspace's own tests (tests/), when no package is named: the quick ones here, the slow ones
# (minutes each) among the slow steps below, a step each; each test file of a folder in
# SPLIT_WORKSPACE_TESTS is a step of its own (tests/student/: a student per file, one lab each).
SLOW_WORKSPACE_TESTS=(network student test_tour.py)
SPLIT_WORKSPACE_TESTS=(student)
if [ $# -eq 0 ] && [ -d "$ROOT/tests" ]; then
    args=()
    for part in "${SLOW_WORKSPACE_TESTS[@]}"; do args+=(--ignore="$ROOT/tests/$part"); done
    echo "test: pytest tests"
    "${PYTEST[@]}" --junitxml="$RESULTS/pytest/workspace.xml" "${args[@]}" "$ROOT/tests" | tail -n 1
    why=$(pytest_failure tests "${PIPESTATUS[0]}") && step_failures+=("$why")
    expected+=(pytest/workspace.xml)
fi

# 2. The slow steps, two or three at a time: every registered rostest (each starts its own master on a free
#    port) and, when no package is named, the workspace's tests in tests/.
jobs_file="$LOGS/jobs.txt"
: > "$jobs_file"
# Steps that measure wall-clock rates, speeds and latencies (a 30 Hz topic's longest gap, how fast
# a node notices a dead master, turtlesim's 62.5 Hz, a turtle's 0.5 m/s, a 10x real-time factor):
# they run first, with nothing beside them.
ALONE=("pytest tests/network" "rostest fake_tb3/test/real_time.test" "rostest turtlesim/test/interface.test"
       "rostest ros_exercises/test/publisher_subscriber.test"
       "rostest compat/turtlebot3_teleop/test/teleop_key.test" "rostest my_turtle/test/stages.test"
       "rostest turtlesim/test/programs.test" "rostest fake_tb3/test/sim_time.test"
       "rostest turtlesim/test/sim_time.test")
# add_job LABEL EXIT_CODES COMMAND...: one line of run_test_jobs.py's list (EXIT_CODES: the statuses
# after which the command's result file tells the rest).
add_job() {
    local sharing=shared
    local step
    for step in "${ALONE[@]}"; do [ "$step" = "$1" ] && sharing=alone; done
    { printf '%s\t%s\t%s\t' "$1" "$2" "$sharing"; shift 2; printf '%q ' "$@"; echo; } >> "$jobs_file"
}
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
        name="workspace-$(echo "${part%.py}" | tr / -)"
        args=()
        if [ "$part" = network ] && [ "$(id -u)" != 0 ] && [ -e "$ROOT/tests/network/test_two_hosts.py" ]; then
            # Two network namespaces need CAP_NET_ADMIN: this test runs where the tests run as root
            # (CI's host side), not as the Docker image's ordinary user.
            echo "test: tests/network/test_two_hosts.py needs root: not run here"
            args+=(--ignore="$ROOT/tests/network/test_two_hosts.py")
        fi
        # Their temporary folders (the tour's pictures and logs) are kept beside the step's log.
        add_job "pytest tests/$part" 0,1 "${PYTEST[@]}" --junitxml="$RESULTS/pytest/$name.xml" \
            --basetemp="$LOGS/$name" "${args[@]}" "$ROOT/tests/$part"
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

if [ -s "$jobs_file" ]; then
    echo "test: building the tests"
    if ! "$ROOT/tools/setup.sh" --make tests -j2 > "$LOGS/test_build.log" 2>&1; then
        tail -n 40 "$LOGS/test_build.log"; step_failures+=("building the tests (log $LOGS/test_build.log)")
    fi
    echo "test: $(wc -l < "$jobs_file") rostests and slow pytests, ${TEST_JOBS:-2 or 3} at a time (logs in ${LOGS#"$ROOT"/})"
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
