#!/usr/bin/env bash
# CI, after tools/docker-test.sh: grades the example classes (examples/grading/) with ./grade.sh in
# containers, the hostile examples included, and checks every score and feedback sentence.
# Usage: tools/grade-test.sh [pytest options]
#        tools/grade-test.sh --platforms [pytest options]   (what tools/platform-test.sh runs: the
#        platforms' tests in the grading image ros-course-grader:bookworm, the first layers of
#        ros-course:bookworm, so it comes out of tools/docker-test.sh's build cache; first, that the
#        image holds what grading needs and no more)
set -euo pipefail
tests=classes_in_containers.py
platforms=no
if [ "${1:-}" = --platforms ]; then
    tests=platforms_in_containers.py
    platforms=yes
    shift
fi
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
"$ROOT/tools/setup.sh"
# shellcheck disable=SC1091
source "$ROOT/tools/env.sh"
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine

# The grading image: every package a grading needs, none of the students' others, and no more
# documentation, manual pages and translations than its base image debian:bookworm had (the
# copyright files aside).
check_grading_image() {
    local grading others docs installed missing extra docs_kb base_docs_kb
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
        return 1
    fi
    echo "platform-test: $image holds the $(echo "$grading" | wc -l) packages of grading, none of the" \
         "$(echo "$others" | wc -l) others; documentation, manual pages and translations: $docs_kb kB" \
         "(debian:bookworm: $base_docs_kb kB)"
}

started=$SECONDS
if [ "$platforms" = yes ]; then
    image=$(course_docker_grading_image bookworm)
else
    image=$(course_docker_image bookworm)
fi
# Made once here; every grading of the tests uses it (by id: the tag may move meanwhile).
COURSE_GRADER_IMAGE=$(docker image inspect -f '{{.Id}}' "$image")
export COURSE_GRADER_IMAGE
echo "grade-test: $image made in $((SECONDS - started)) s, $(($(docker image inspect -f '{{.Size}}' "$image") / 1000000)) MB"
[ "$platforms" = no ] || check_grading_image
# Not exec: the EXIT trap of tools/docker.sh must still stop a dockerd it started.
/usr/bin/python3 -m pytest -v --durations=0 -p no:cacheprovider "$ROOT/src/course_grader/test/$tests" "$@"
