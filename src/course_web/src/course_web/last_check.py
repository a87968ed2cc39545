"""The student's last checks (`rosrun course_grader check LAB`), kept where the browser view finds
them, so that a student with only a browser sees them (no ROS here):

    ROS_HOME/course_check/LAB/STAMP/check.json         what the check showed (course_grader.check)
    ROS_HOME/course_check/LAB/STAMP/FOLDER/...         the grader's folder: pictures, logs, runs
    ROS_HOME/course_check/latest -> LAB/STAMP          the last check, of any lab

The last KEEP_PER_LAB checks of each lab are kept. The view serves only the known files of a check
(check.json, FOLDER/*.png, FOLDER/*.replay.js), each a plain file under the root: no other name,
no '..', no symbolic link on the way."""
import json
import os
import re
import shutil
import stat
import time

KEEP_PER_LAB = 5
ROOT_NAME = 'course_check'
LATEST = 'latest'
SUMMARY = 'check.json'
STAMP_FORMAT = '%Y-%m-%d_%H-%M-%S'
_STAMP = re.compile(r'\d{4}-\d{2}-\d{2}_\d{2}-\d{2}-\d{2}(_\d+)?')
_NAME = re.compile(r'[A-Za-z0-9][A-Za-z0-9_.+-]*')   # no leading dot: not '..', not a hidden file
# What a student folder's files are served as, by how their names end.
CONTENT_TYPES = (('.replay.js', 'text/javascript; charset=utf-8'), ('.png', 'image/png'))


def default_root():
    """ROS_HOME/course_check (ROS_HOME defaults to ~/.ros), as the check and the view both use it."""
    import rospkg
    return os.path.join(rospkg.get_ros_home(), ROOT_NAME)


def new_check_folder(root, lab, now=None):
    """A new, empty folder ROOT/LAB/STAMP for a check of LAB (STAMP: the local time, sortable)."""
    stamp = time.strftime(STAMP_FORMAT, time.localtime(now))
    os.makedirs(os.path.join(root, lab), exist_ok=True)
    for count in range(1, 1000):
        folder = os.path.join(root, lab, stamp if count == 1 else '%s_%d' % (stamp, count))
        try:
            os.mkdir(folder)
            return folder
        except FileExistsError:
            continue
    raise FileExistsError('no free folder for a check in %s' % os.path.join(root, lab))


def write_summary(folder, summary):
    """check.json in a check's folder, whole or not at all (a page may read it meanwhile)."""
    path = os.path.join(folder, SUMMARY)
    with open(path + '.part', 'w', encoding='utf-8') as stream:
        json.dump(summary, stream, indent=1, sort_keys=True)
    os.replace(path + '.part', path)


def point_latest(root, folder):
    """ROOT/latest made to point at the check in `folder` (ROOT/LAB/STAMP), replaced at once."""
    target = os.path.relpath(folder, root)
    link = os.path.join(root, LATEST)
    making = link + '.%d' % os.getpid()
    if os.path.lexists(making):
        os.remove(making)
    os.symlink(target, making)
    os.replace(making, link)


def latest_check(root):
    """'LAB/STAMP' of the last check, or None (no check yet, or a pointer that is not one of ours)."""
    try:
        target = os.readlink(os.path.join(root, LATEST))
    except OSError:
        return None
    parts = target.split('/')
    if len(parts) != 2 or not _NAME.fullmatch(parts[0]) or not _STAMP.fullmatch(parts[1]):
        return None
    return target if _plain(root, parts, stat.S_ISDIR) else None


def prune(root, lab, keep=KEEP_PER_LAB):
    """Remove all but the last `keep` checks of LAB (never the one latest points at); the names removed."""
    lab_folder = os.path.join(root, lab)
    stamps = sorted(name for name in os.listdir(lab_folder) if _STAMP.fullmatch(name)
                    and _plain(root, [lab, name], stat.S_ISDIR))
    latest = latest_check(root)
    removed = [name for name in stamps[:max(0, len(stamps) - keep)] if '%s/%s' % (lab, name) != latest]
    for name in removed:
        shutil.rmtree(os.path.join(lab_folder, name))
    return removed


def served_file(root, path):
    """(file path, content type) of a check's file the view serves at check/PATH, or None.
    PATH is LAB/STAMP/check.json, or LAB/STAMP/FOLDER/NAME.png or NAME.replay.js."""
    parts = path.split('/')
    if not 3 <= len(parts) <= 4 or not all(_NAME.fullmatch(part) for part in parts) \
            or not _STAMP.fullmatch(parts[1]):
        return None
    if len(parts) == 3:
        content_type = 'application/json; charset=utf-8' if parts[2] == SUMMARY else None
    else:
        content_type = next((kind for ending, kind in CONTENT_TYPES if parts[3].endswith(ending)), None)
    if content_type is None or not _plain(root, parts, stat.S_ISREG):
        return None
    return os.path.join(root, *parts), content_type


def _plain(root, parts, is_kind):
    """Whether ROOT/parts... exists with no symbolic link on the way below root, and is of its kind."""
    path = root
    for index, part in enumerate(parts):
        path = os.path.join(path, part)
        try:
            mode = os.lstat(path).st_mode
        except OSError:
            return False
        last = index == len(parts) - 1
        if not (is_kind(mode) if last else stat.S_ISDIR(mode)):
            return False
    return True
