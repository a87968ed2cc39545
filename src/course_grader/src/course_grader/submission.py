"""A student's submission: a folder, a .zip or a .tar.gz, unpacked safely and searched for the lab's
package. Nothing here runs the student's code."""
import collections
import os
import re
import stat
import tarfile
import unicodedata
import zipfile

# An archive bigger than this when unpacked, or with more members, is refused (an archive bomb).
MAX_UNPACKED_BYTES = 200 * 1024 * 1024
MAX_MEMBERS = 5000
ARCHIVE_SUFFIXES = ('.tar.gz', '.tgz', '.zip')


class SubmissionError(Exception):
    """The submission cannot be graded; the message is the reason, for the student's row."""


# The names a learning platform's "download all" gives a student's upload (docs/grading.md):
# Moodle, a folder `Full Name_ID_assignsubmission_file_`; Canvas, a file
# `lastnamefirstname[_late]_ID_SUBMISSION_uploaded-name`.
MOODLE_FOLDER = re.compile(r'^(?P<name>.+?)_(?P<id>\d+)_assignsubmission_[a-z]+_?$')
CANVAS_FILE = re.compile(r'^(?P<name>[^_]+)_(?:late_)?(?P<id>\d+)_\d+_.+$', re.I)

Student = collections.namedtuple('Student', 'name id folder')
Student.__doc__ = ('Who handed a submission in: the name as the platform wrote it, the platform\'s id '
                   '(\'\' when there is none) and a folder name made of them that is safe in a path.')


def safe_name(text):
    """text as a file name: letters (any script) and digits kept, '.', '_' and '-' too, the rest '_'."""
    kept = ''.join(c if c.isalnum() or c in '._-' else '_' for c in unicodedata.normalize('NFC', text))
    return kept.strip('._') or 'student'


def ascii_name(text):
    """text for names that allow ASCII only (containers): accents dropped, then as safe_name."""
    folded = unicodedata.normalize('NFKD', text).encode('ascii', 'ignore').decode()
    return re.sub(r'[^A-Za-z0-9._-]', '_', folded).strip('._-') or 'student'


def student_of(path):
    """The Student of a submission, from its folder's or file's name."""
    base = unicodedata.normalize('NFC', os.path.basename(os.path.normpath(path)))
    moodle = MOODLE_FOLDER.match(base)
    canvas = CANVAS_FILE.match(base) if not os.path.isdir(path) else None
    if moodle or canvas:
        name, platform_id = (moodle or canvas).group('name', 'id')
        return Student(name, platform_id, '%s_%s' % (safe_name(name), platform_id))
    for suffix in ARCHIVE_SUFFIXES:
        if base.endswith(suffix):
            base = base[:-len(suffix)]
            break
    return Student(base, '', safe_name(base))


def _safe_member_path(destination, name):
    """Where an archive member would land, or a SubmissionError if that is outside destination."""
    if name.startswith('/') or '\\' in name:
        raise SubmissionError('the archive holds %r, an absolute path: refused' % name)
    target = os.path.normpath(os.path.join(destination, name))
    if target != destination and not target.startswith(destination + os.sep):
        raise SubmissionError('the archive holds %r, which points outside its folder: refused' % name)
    return target


def _check_link(destination, member_path, link_target):
    if os.path.isabs(link_target):
        raise SubmissionError('the archive holds a link %r to %r, outside its folder: refused'
                              % (os.path.relpath(member_path, destination), link_target))
    _safe_member_path(destination, os.path.relpath(
        os.path.join(os.path.dirname(member_path), link_target), destination))


def _extract_tar(archive, destination):
    try:
        tar = tarfile.open(archive, 'r:*')
    except (tarfile.TarError, OSError) as error:
        raise SubmissionError('%s is not a readable .tar.gz archive (%s)' % (os.path.basename(archive), error))
    with tar:
        members, total = [], 0
        for member in tar:
            members.append(member)
            if len(members) > MAX_MEMBERS:
                raise SubmissionError('the archive has more than %d files: refused' % MAX_MEMBERS)
            target = _safe_member_path(destination, member.name)
            if member.issym() or member.islnk():
                _check_link(destination, target, member.linkname if member.issym()
                            else os.path.relpath(os.path.join(destination, member.linkname),
                                                 os.path.dirname(target)))
            elif not (member.isfile() or member.isdir()):
                raise SubmissionError('the archive holds %r, a device or pipe: refused' % member.name)
            total += max(member.size, 0)
            if total > MAX_UNPACKED_BYTES:
                raise SubmissionError('the archive unpacks to more than %d MB: refused'
                                      % (MAX_UNPACKED_BYTES // 2 ** 20))
        for member in members:
            target = _safe_member_path(destination, member.name)
            if member.isdir():
                os.makedirs(target, exist_ok=True)
            elif member.issym():
                os.makedirs(os.path.dirname(target), exist_ok=True)
                os.symlink(member.linkname, target)
            elif member.isfile():
                os.makedirs(os.path.dirname(target), exist_ok=True)
                _copy_limited(tar.extractfile(member), target, member.size)
                os.chmod(target, 0o755 if member.mode & 0o111 else 0o644)
            # hard links: checked above, not made (none of a course package needs one)


def _copy_limited(source, target, size):
    written = 0
    with open(target, 'wb') as out:
        while True:
            chunk = source.read(1 << 16)
            if not chunk:
                break
            written += len(chunk)
            if written > size or written > MAX_UNPACKED_BYTES:
                raise SubmissionError('an archive member is bigger than it says: refused')
            out.write(chunk)


def _extract_zip(archive, destination):
    try:
        zipped = zipfile.ZipFile(archive)
    except (zipfile.BadZipFile, OSError) as error:
        raise SubmissionError('%s is not a readable .zip archive (%s)' % (os.path.basename(archive), error))
    with zipped:
        infos = zipped.infolist()
        if len(infos) > MAX_MEMBERS:
            raise SubmissionError('the archive has more than %d files: refused' % MAX_MEMBERS)
        if sum(info.file_size for info in infos) > MAX_UNPACKED_BYTES:
            raise SubmissionError('the archive unpacks to more than %d MB: refused'
                                  % (MAX_UNPACKED_BYTES // 2 ** 20))
        for info in infos:
            target = _safe_member_path(destination, info.filename)
            mode = info.external_attr >> 16
            if stat.S_ISLNK(mode):
                raise SubmissionError('the archive holds a link %r: refused (zip links are not needed)'
                                      % info.filename)
            if info.is_dir():
                os.makedirs(target, exist_ok=True)
                continue
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with zipped.open(info) as source:
                _copy_limited(source, target, info.file_size)
            os.chmod(target, 0o755 if mode & 0o111 else 0o644)


def check_folder(folder):
    """Refuse a submission folder with links that point outside it (in an archive or not)."""
    folder = os.path.realpath(folder)
    for parent, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(parent, name)
            if os.path.islink(path):
                target = os.path.realpath(path)
                if target != folder and not target.startswith(folder + os.sep):
                    raise SubmissionError('%s is a link to %s, outside the submission: refused'
                                          % (os.path.relpath(path, folder), os.readlink(path)))


def upload_inside(folder):
    """The one archive a platform's folder holds (Moodle keeps a student's upload so), or None when
    the folder itself is the submission (it has a package.xml, or no archive at its top)."""
    for parent, dirs, files in os.walk(folder):
        if 'package.xml' in files:
            return None
    archives = sorted(name for name in os.listdir(folder) if name.endswith(ARCHIVE_SUFFIXES)
                      and not name.startswith('.') and os.path.isfile(os.path.join(folder, name)))
    if len(archives) > 1:
        raise SubmissionError('the folder holds %d archives and no package.xml (%s): hand in one'
                              % (len(archives), ', '.join(archives)))
    return os.path.join(folder, archives[0]) if archives else None


def unpack(path, destination):
    """The submission's folder: `path` itself if it is a folder, or the one archive it holds, or
    the archive `path` unpacked into destination (which must exist and be empty)."""
    if os.path.isdir(path):
        check_folder(path)
        inside = upload_inside(path)
        if inside is None:
            return os.path.realpath(path)
        path = inside
    if not os.path.exists(path):
        raise SubmissionError('%s does not exist' % path)
    destination = os.path.realpath(destination)
    if path.endswith('.zip'):
        _extract_zip(path, destination)
    elif path.endswith(('.tar.gz', '.tgz')):
        _extract_tar(path, destination)
    else:
        raise SubmissionError('%s is neither a folder nor a .zip or .tar.gz archive' % os.path.basename(path))
    check_folder(destination)
    return destination


def package_name(package_xml):
    try:
        with open(package_xml, errors='replace') as stream:
            text = stream.read(200000)
    except OSError:
        return None
    match = re.search(r'<name>\s*([^<\s]+)\s*</name>', text)
    return match.group(1) if match else None


def find_package(folder, package, max_depth=4):
    """The folder of the package named `package` in a submission (the package folder itself, a
    folder holding it, or a workspace with src/), relative to the submission folder."""
    found, others = [], []
    folder = os.path.realpath(folder)
    for parent, dirs, files in os.walk(folder):
        depth = os.path.relpath(parent, folder).count(os.sep) + (parent != folder)
        dirs[:] = sorted(d for d in dirs if not d.startswith('.') and d not in ('build', 'devel')
                         and depth < max_depth)
        if 'package.xml' in files:
            name = package_name(os.path.join(parent, 'package.xml'))
            (found if name == package else others).append((name, os.path.relpath(parent, folder)))
    if not found:
        seen = ', '.join('%s (%s)' % item for item in others) or 'none'
        raise SubmissionError('no package named %s in the submission (a folder with a package.xml '
                              'saying <name>%s</name>); packages found: %s' % (package, package, seen))
    if len(found) > 1:
        raise SubmissionError('the package %s is there %d times (%s): hand in one'
                              % (package, len(found), ', '.join(path for _, path in found)))
    return found[0][1]


def find_file(folder, name):
    """Paths (relative to folder) of the files called `name` under folder, sorted, scripts/ first."""
    hits = []
    for parent, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith('.'))
        if name in files:
            hits.append(os.path.relpath(os.path.join(parent, name), folder))
    return sorted(hits, key=lambda p: (not p.startswith('scripts' + os.sep), p.count(os.sep), p))
