#!/usr/bin/env bash
# CI, after tools/grade-test.sh: the platforms' side of the grading run here as the platforms run it
# (src/course_grader/test/platforms_in_containers.py): the GitHub Classroom workflow's steps in
# order on example students and bad pushes, and Gradescope's run_autograder, in the grading image
# the platforms are given (ros-course-grader:bookworm, tools/docker.sh: the first layers of
# ros-course:bookworm, which tools/docker-test.sh built, so it comes out of the build cache).
# First, that the grading image holds what grading needs and no more: none of the packages below
# the package list's `# ====` line, no documentation.
# Usage: tools/platform-test.sh [pytest options]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
"$ROOT/tools/setup.sh"
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine
started=$SECONDS
image=$(course_docker_grading_image bookworm)
# Made once here; every grading of the tests uses it (by id: the tag may move meanwhile).
COURSE_GRADER_IMAGE=$(docker image inspect -f '{{.Id}}' "$image")
export COURSE_GRADER_IMAGE
echo "platform-test: $image made in $((SECONDS - started)) s, $(($(docker image inspect -f '{{.Size}}' "$image") / 1000000)) MB"

# The grading image: every package a grading needs, none of the students' others, and no more
# documentation, manual pages and translations than its base image debian:bookworm had (the
# copyright files aside).
grading=$("$ROOT/tools/setup.sh" --packages --grading | sort)
others=$(comm -13 <(echo "$grading") <("$ROOT/tools/setup.sh" --packages | sort))
docs='find /usr/share/doc /usr/share/man /usr/share/info /usr/share/locale -type f ! -name copyright -printf "%s\n" 2>/dev/null | awk "{ b += \$1 } END { print int(b / 1024) }"'
# shellcheck disable=SC2086
installed=$(docker run --rm --network none --entrypoint bash "$COURSE_GRADER_IMAGE" -c \
    'dpkg-query -W -f="\${Status} \${Package}\n" "$@" 2>/dev/null | sed -n "s/^install ok installed //p"' \
    grading $grading $others | sort)
missing=$(comm -23 <(echo "$grading") <(echo "$installed"))
extra=$(comm -12 <(echo "$others") <(echo "$installed"))
docs_kb=$(docker run --rm --network none --entrypoint bash "$COURSE_GRADER_IMAGE" -c "$docs")
base_docs_kb=$(docker run --rm --network none debian:bookworm bash -c "$docs")
if [ -n "$missing$extra" ] || [ "$docs_kb" -gt $((base_docs_kb + 1024)) ]; then
    echo "platform-test: the grading image $image is not what grading needs and no more:" \
         "${missing:+missing: $(echo $missing);} ${extra:+not for grading: $(echo $extra);}" \
         "documentation, manual pages and translations: $docs_kb kB (debian:bookworm: $base_docs_kb kB)" >&2
    exit 1
fi
echo "platform-test: $image holds the $(echo "$grading" | wc -l) packages of grading, none of the" \
     "$(echo "$others" | wc -l) others; documentation, manual pages and translations: $docs_kb kB" \
     "(debian:bookworm: $base_docs_kb kB)"
# Not exec: the EXIT trap of tools/docker.sh must still stop a dockerd it started.
/usr/bin/python3 -m pytest -v -s -p no:cacheprovider "$ROOT/src/course_grader/test/platforms_in_containers.py" "$@"
