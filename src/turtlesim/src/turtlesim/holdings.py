"""What a turtle holds, and the node's room for open files (pure: no rospy, unit-tested without ROS).

A turtle holds publishers, a subscriber and services. They are made one by one and each can fail
(a refused registration, no file left). Holdings makes them all or none: a failure releases what
was already made, and releasing goes on past an error so that one stuck item does not keep the others.
"""
import os
import resource

# Open files kept free for what must work at the limit: a /kill, a service call, a registration with
# the master (one socket each while they run). A spawn is refused when fewer are free.
FILE_RESERVE = 32


class Holdings:
    """The items one owner holds, each with the function that gives it back."""

    def __init__(self):
        self._held = []  # (label, item, release), oldest first

    def take(self, label, create, release):
        """Make an item with create() and keep it with its release(item); returns the item."""
        item = create()
        self._held.append((label, item, release))
        return item

    def take_all(self, steps):
        """take() every (label, create, release) of steps and return the items; on any failure release
        what was taken (also what this Holdings held before) and re-raise."""
        try:
            return [self.take(label, create, release) for label, create, release in steps]
        except BaseException:
            self.release_all()
            raise

    def labels(self):
        return [label for label, _, _ in self._held]

    def __len__(self):
        return len(self._held)

    def release_all(self):
        """Release everything, newest first, even past failures; returns [(label, exception)] of those that failed."""
        failures = []
        while self._held:
            label, item, release = self._held.pop()
            try:
                release(item)
            except Exception as error:  # a failed release must not keep the rest
                failures.append((label, error))
        return failures


def raise_open_file_limit(limits=resource):
    """Raise the soft open-file limit (ulimit -n) to the hard one; returns (soft, hard) afterwards."""
    soft, hard = limits.getrlimit(limits.RLIMIT_NOFILE)
    if hard == limits.RLIM_INFINITY or soft == limits.RLIM_INFINITY or soft < hard:
        try:
            limits.setrlimit(limits.RLIMIT_NOFILE, (hard, hard))
        except (ValueError, OSError):  # e.g. an infinite hard limit the kernel caps lower: keep the soft one
            return soft, hard
        soft = hard
    return soft, hard


def open_file_count(fd_dir='/proc/self/fd'):
    """How many files this process has open; None if that cannot be read (no /proc, or no file left)."""
    try:
        return len(os.listdir(fd_dir))
    except OSError:
        return None


def open_file_limit(limits=resource):
    return limits.getrlimit(limits.RLIMIT_NOFILE)[0]


def spawn_refusal(requested_name, open_files, limit, reserve=FILE_RESERVE):
    """The error text of a spawn that must be refused for want of open files, or None if it may go on.

    open_files None means the count could not be read, which happens when no file is left."""
    if limit is None or limit < 0 or limit == resource.RLIM_INFINITY:
        return None
    if open_files is not None and limit - open_files >= reserve:
        return None
    turtle = 'turtle [%s]' % requested_name if requested_name else 'a turtle'
    used = 'all' if open_files is None else '%d' % open_files
    return ('Cannot spawn %s: turtlesim has %s of its %d open files in use (ulimit -n) and keeps %d free '
            'for kill and other calls; close connections to its topics or kill turtles, or start it with a '
            'higher limit' % (turtle, used, limit, reserve))


# Below this limit turtlesim says at start what the limit lets it hold.
LOW_FILE_LIMIT = 4096


def capacity_note(limit, base_files, reserve=FILE_RESERVE):
    """The start-up line that says what an open-file limit lets turtlesim hold."""
    room = max(0, limit - base_files - reserve)
    return ('Open-file limit %d: a turtle holds no open file, each connection to a turtle topic '
            '(a subscriber of its pose or color_sensor, a publisher on its cmd_vel) holds one: room for '
            'about %d connections, e.g. %d turtles each driven and watched' % (limit, room, room // 2))
