# Sourced by setup.sh/setup.bash of this workspace and of every workspace built on top of it, so
# that a terminal which only sources a devel/setup.bash (as the slides teach) runs ROS as
# tools/env.sh does. POSIX sh: setup.sh sources this file from sh, bash and zsh.

# ROS from Debian lives in /usr/bin's python3 (and `python`, from python-is-python3): /usr/bin goes
# first, before any pyenv or conda interpreter without rospy. Moved, not added: sourcing again
# leaves PATH as it was.
_course_path=
_course_rest="$PATH:"
while [ -n "$_course_rest" ]; do
    _course_entry="${_course_rest%%:*}"
    _course_rest="${_course_rest#*:}"
    if [ "$_course_entry" != /usr/bin ]; then
        _course_path="${_course_path}:${_course_entry}"
    fi
done
PATH="/usr/bin${_course_path}"
export PATH
unset _course_path _course_rest _course_entry

# Packages pip put in ~/.local must not hide Debian's (numpy, yaml) from ROS's python3.
PYTHONNOUSERSITE=1
export PYTHONNOUSERSITE
ROS_MASTER_URI="${ROS_MASTER_URI:-http://localhost:11311}"
export ROS_MASTER_URI
