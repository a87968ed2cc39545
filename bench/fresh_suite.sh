#!/usr/bin/env bash
# The README's figure: ./test.sh from a clone of HEAD on a fresh Debian machine, apt included, as a
# container of the minimal debian:SUITE base image (tools/docker.sh makes it with debootstrap), root,
# with NET_ADMIN and SYS_ADMIN so that tests/network/test_two_hosts.py runs as on a real machine.
#   bench/fresh_suite.sh [SUITE]      (bookworm, the default, or trixie)
# Prints the set-up's end and the closing line with their times, then the whole run's wall time, and
# keeps the run's timeline (test.sh's build/test_logs/timeline.txt) as build/fresh-suite-timeline.txt.
# Run it with nothing else on the machine: the figure is wall time.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
suite=${1:-bookworm}
# shellcheck source=tools/docker.sh
source "$ROOT/tools/docker.sh"
course_docker_engine
docker image inspect "debian:$suite" > /dev/null 2>&1 || _course_docker_base_image "$suite"
clone=$(mktemp -d /var/tmp/fresh-suite.XXXXXX)
trap 'rm -rf "$clone"; course_docker_stop' EXIT   # course_docker_engine's own trap, replaced here
git clone -q --no-hardlinks "$ROOT" "$clone/ws"
proxy=$(_course_apt_proxy)
echo "fresh-suite: ./test.sh in debian:$suite, a clone of $(git -C "$ROOT" rev-parse --short HEAD), load $(cut -d' ' -f1-3 /proc/loadavg)"
start=$(date +%s)
status=0
docker run --rm --network host --cap-add NET_ADMIN --cap-add SYS_ADMIN ${proxy:+-e "http_proxy=$proxy"} \
    -v "$clone/ws:/ws" -w /ws "debian:$suite" ./test.sh 2>&1 \
    | while IFS= read -r line; do
        case "$line" in
            "test: building the tests"|*" passed, "*" failed"|*FAILED*|"test: at most"*)
                printf '%4d s  %s\n' $(( $(date +%s) - start )) "$line" ;;
        esac
    done || status=$?   # the suite's own status, after the time is printed
seconds=$(( $(date +%s) - start ))
mkdir -p "$ROOT/build"
cp "$clone/ws/build/test_logs/timeline.txt" "$ROOT/build/fresh-suite-timeline.txt" 2>/dev/null \
    && echo "fresh-suite: the steps' timeline is in build/fresh-suite-timeline.txt"
printf 'fresh-suite: %d min %d s in all (load now %s)\n' $((seconds / 60)) $((seconds % 60)) "$(cut -d' ' -f1-3 /proc/loadavg)"
exit "$status"
