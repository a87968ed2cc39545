#!/usr/bin/env bash
# The course's demo: installs what is missing, builds, and runs the tour of the labs, headless.
#   ./demo.sh            every lab, one after the other
#   ./demo.sh square     only the labs named (./demo.sh --help lists them)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$ROOT/tools/setup.sh"
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"
exec rosrun course_tour tour "$@"
