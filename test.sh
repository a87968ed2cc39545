#!/usr/bin/env bash
# Runs every test of the workspace: ./test.sh        (or only some packages: ./test.sh turtlesim my_turtle)
# Installs what is missing, builds, runs the pure tests (pytest) and the rostests, and ends with one
# line `N passed, N failed`. Exit status 0 only if everything ran and passed.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"
"$ROOT/tools/setup.sh" || exit 1
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"

BASE="${CATKIN_BUILD_BASE:-$ROOT}"
RESULTS="$BASE/build/test_results"
rm -rf "$RESULTS"
mkdir -p "$RESULTS/pytest"
export DISPLAY=   # the tests start their own Xvfb where they need a screen

if [ $# -gt 0 ]; then packages=("$@"); else
    mapfile -t packages < <(catkin_topological_order --only-names "$ROOT/src")
fi
step_failures=()

# 1. Pure tests: no master, milliseconds each.
unit_dirs=()
for pkg in "${packages[@]}"; do
    dir=$(dirname "$(grep -l "<name>$pkg</name>" "$ROOT"/src/*/package.xml "$ROOT"/src/*/*/package.xml 2>/dev/null | head -n1)")
    [ -d "$dir/test/unit" ] && unit_dirs+=("$dir/test/unit")
done
[ $# -eq 0 ] && unit_dirs+=("$ROOT/tests")
if [ ${#unit_dirs[@]} -gt 0 ]; then
    echo "test: pytest ${unit_dirs[*]}"
    /usr/bin/python3 -m pytest -q -p no:cacheprovider --junitxml="$RESULTS/pytest/pytest.xml" "${unit_dirs[@]}"
    rc=$?
    [ $rc -ne 0 ] && [ $rc -ne 1 ] && step_failures+=("pytest (exit $rc)")
fi

# 2. rostests, one after the other (each starts its own master on a free port).
catkin_args=(--directory "$ROOT" --build "$BASE/build" -DCATKIN_DEVEL_PREFIX="$BASE/devel"
             -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCATKIN_WHITELIST_PACKAGES="${CATKIN_WHITELIST:-}")
if [ $# -gt 0 ]; then targets=(); for pkg in "${packages[@]}"; do targets+=("run_tests_$pkg"); done
else targets=(run_tests); fi
echo "test: rostest (${targets[*]})"
if ! catkin_make "${catkin_args[@]}" tests -j2 > "$BASE/build/test_build.log" 2>&1; then
    tail -n 40 "$BASE/build/test_build.log"; step_failures+=("building the tests")
fi
catkin_make "${catkin_args[@]}" "${targets[@]}" -j1 2>&1 | grep -E "^\[(ROSTEST|ROSUNIT)\]|FAILURE|ERROR|^-- run_tests|rostest --" || true

# 3. One count over everything that ran.
/usr/bin/python3 "$ROOT/tools/count_results.py" "$RESULTS" "${step_failures[@]}"
