"""A student's submission: a folder, a .zip or a .tar.gz, unpacked safely and searched for the lab's
package. Nothing here runs the student's code.

An archive makes regular files (mode 0o644, 0o755 when the archive gives any execute bit) and
folders (0o755) inside the destination, and nothing else. Each member is written one path component
at a time: every folder is opened without following a link, every file is created new
(O_NOFOLLOW | O_EXCL), so nothing is ever written through a link, whatever order the archive has.
Every other member is skipped, not created, and named in `skipped`: symbolic and hard links (in a
.tar.gz, or marked so in a .zip; a catkin workspace's src/CMakeLists.txt links to Debian's
toplevel.cmake, which the grader's own workspace provides), devices, FIFOs and sockets.
The whole archive is refused (SubmissionError), before anything is written, for a name that is
absolute or holds `..`, a file named twice, a name that is both a file and a folder (`a`, then
`a/b`), more than MAX_MEMBERS members or more than MAX_UNPACKED_BYTES; and, while writing, for a
member bigger than it says or an archive that cannot be read. Names are Unicode NFC, as student_of's,
and '\\' separates folders as '/' does (Windows tools write it so).
A plain folder is refused when it holds a FIFO, a socket, a device or a link that leads outside it."""
import collections
import datetime
import lzma
import os
import re
import stat
import subprocess
import tarfile
import tempfile
import threading
import unicodedata
import zipfile
import zlib

# An archive bigger than this when unpacked, or with more members, is refused (an archive bomb).
MAX_UNPACKED_BYTES = 200 * 1024 * 1024
MAX_MEMBERS = 5000
ARCHIVE_SUFFIXES = ('.tar.gz', '.tgz', '.zip')
# What reading a damaged or unusual archive raises (a bad CRC, a truncated stream, an encrypted or
# unknown compression method in a .zip): each becomes the student's reason.
UNREADABLE = (tarfile.TarError, zipfile.BadZipFile, zlib.error, lzma.LZMAError, EOFError, NotImplementedError,
              RuntimeError, ValueError, OSError)


class SubmissionError(Exception):
    """The submission cannot be graded; the message is the reason, for the student's row."""


# The names a learning platform's "download all" gives a student's upload (docs/grading.md):
# Moodle, a folder `Full Name_ID_assignsubmission_file_`; Canvas, a file
# `lastnamefirstname[_late]_ID_SUBMISSION_uploaded-name`. A name may hold any character, a line break too.
MOODLE_FOLDER = re.compile(r'^(?P<name>.+?)_(?P<id>\d+)_assignsubmission_[a-z]+_?$', re.S)
CANVAS_FILE = re.compile(r'^(?P<name>[^_]+)_(?:late_)?(?P<id>\d+)_\d+_.+$', re.I | re.S)

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


# What starts a formula in a spreadsheet (OWASP, CSV injection): a Moodle folder named
# `=HYPERLINK(...)_4712_assignsubmission_file_` would give a cell that runs.
FORMULA_STARTS = ('=', '+', '-', '@', '\t', '\r')


def spreadsheet_cell(value):
    """A CSV cell: a number as a number (-1.5 too), any text inert: one that a spreadsheet would
    take for a formula gets a leading quote, which shows it as the text it is."""
    if isinstance(value, (int, float)):
        return '%g' % value
    text = str(value)
    return "'" + text if text.startswith(FORMULA_STARTS) else text


def terminal_text(text, keep_lines=False):
    """text (a student's name, a reason quoting what a student's code printed) as a terminal must
    show it: line breaks, escape sequences, other control and format characters (bidirectional
    overrides) written as Python writes them in a string ('\\n', '\\x1b', '\\u202e'); one line, or
    with keep_lines its own lines, each made so."""
    if keep_lines:
        return '\n'.join(terminal_text(line) for line in str(text).split('\n'))
    return ''.join(c if c.isprintable() else repr(c)[1:-1] for c in str(text))


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


Submitted = collections.namedtuple('Submitted', 'time source claim')
Submitted.__doc__ = ('When a submission was handed in: an aware datetime, or None when it is not known; '
                     'where that was read (a sentence, or why no time is known); and whether it is the '
                     'student\'s own claim (a commit date, which the student can set) rather than a platform\'s.')

GIT_SECONDS = 10          # reading a clone's last commit: a .git that makes git wait is given up on
COMMIT_HEAD_BYTES = 65536  # a commit's header (its committer line) comes before its message
SHA = re.compile(r'^[0-9a-f]{40}([0-9a-f]{24})?$')
REF = re.compile(r'^refs/[A-Za-z0-9._/-]{1,200}$')
COMMITTER = re.compile(rb'^committer .*> (-?\d{1,30}) [+-]\d{4}$', re.M)


KEEP_TIMES = 'unpack the download with unzip, which keeps them'
UNPACKED_SECONDS = 2   # a file whose time is its inode's change time was written so, not given a time


def _file_time(path, follow=False):
    """The time an archive or a download gave a file, as an aware datetime (UTC); None when it has
    none: no time at all, or the time the file was written here (its modification time is its
    change time: unpacked by a tool that keeps no times, such as python3 -m zipfile, or copied)."""
    try:
        status = (os.stat if follow else os.lstat)(path)
        if abs(status.st_ctime - status.st_mtime) < UNPACKED_SECONDS:
            return None
        return datetime.datetime.fromtimestamp(status.st_mtime, datetime.timezone.utc)
    except (OverflowError, OSError, ValueError):
        return None


def _small_text(path, limit=4096):
    """The text of a small regular file, not followed if it is a link; None otherwise."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError:
        return None
    with os.fdopen(fd, 'rb') as stream:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        return stream.read(limit).decode('ascii', errors='replace')


def _head_commit(git_dir):
    """The commit HEAD names in a .git folder, read from its files (HEAD, refs/, packed-refs), or a
    sentence saying why there is none."""
    head = _small_text(os.path.join(git_dir, 'HEAD'))
    if head is None:
        return None, 'its .git has no readable HEAD'
    head = head.strip()
    if SHA.match(head):
        return head, None
    ref = head[len('ref:'):].strip() if head.startswith('ref:') else ''
    if not REF.match(ref) or '..' in ref:
        return None, 'its .git/HEAD names no branch that can be read'
    loose = _small_text(os.path.join(git_dir, *ref.split('/')))
    if loose is not None and SHA.match(loose.strip()):
        return loose.strip(), None
    for line in (_small_text(os.path.join(git_dir, 'packed-refs'), 1 << 20) or '').splitlines():
        sha, _, name = line.partition(' ')
        if name == ref and SHA.match(sha):
            return sha, None
    return None, 'its branch has no commit'


def _commit_time(folder):
    """The committer time of the last commit of a clone (a Submitted), read without the clone's
    config or hooks: HEAD is resolved from the .git files, and git (in a repository of our own, the
    clone's objects only) prints that one commit."""
    source = 'the last commit of the clone'
    git_dir = os.path.join(folder, '.git')
    mode = os.lstat(git_dir).st_mode
    if not stat.S_ISDIR(mode):
        return Submitted(None, 'its .git is %s, not a folder: not read' % (
            'a file' if stat.S_ISREG(mode) else _what_is(mode)), True)
    objects = os.path.join(git_dir, 'objects')
    if not os.path.isdir(objects) or os.path.islink(objects):
        return Submitted(None, 'its .git/objects is not a folder: not read', True)
    sha, why = _head_commit(git_dir)
    if sha is None:
        return Submitted(None, why, True)
    with tempfile.TemporaryDirectory(prefix='course-git-') as own:
        os.makedirs(os.path.join(own, 'repo', 'refs'))
        with open(os.path.join(own, 'repo', 'HEAD'), 'w') as stream:
            stream.write(sha + '\n')
        env = {'PATH': '/usr/bin:/bin', 'HOME': own, 'LC_ALL': 'C', 'GIT_CONFIG_NOSYSTEM': '1',
               'GIT_CONFIG_GLOBAL': os.devnull, 'GIT_DIR': os.path.join(own, 'repo'),
               'GIT_OBJECT_DIRECTORY': objects, 'GIT_NO_REPLACE_OBJECTS': '1', 'GIT_TERMINAL_PROMPT': '0'}
        try:
            git = subprocess.Popen(['git', '-c', 'core.hooksPath=/dev/null', 'cat-file', 'commit', sha], env=env,
                                   cwd=own, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                   stderr=subprocess.DEVNULL, start_new_session=True)
        except OSError:
            return Submitted(None, 'git cannot be run here to read the clone', True)
        # Only the header is read (a commit's message may be huge); git is stopped then, or at the time-out.
        timed_out = threading.Event()
        timer = threading.Timer(GIT_SECONDS, lambda: (timed_out.set(), git.kill()))
        timer.start()
        try:
            header = git.stdout.read(COMMIT_HEAD_BYTES)
        finally:
            timer.cancel()
            git.kill()
            git.wait()
            git.stdout.close()
        if timed_out.is_set():
            return Submitted(None, 'reading its last commit took more than %d s: given up' % GIT_SECONDS, True)
    found = COMMITTER.search(header.split(b'\n\n', 1)[0])
    if not found:
        return Submitted(None, 'its last commit cannot be read', True)
    try:
        return Submitted(datetime.datetime.fromtimestamp(int(found.group(1)), datetime.timezone.utc), source, True)
    except (OverflowError, OSError, ValueError):
        return Submitted(None, 'its last commit gives a date that is no time (%s s after 1970)'
                         % found.group(1).decode()[:40], True)


def submitted(path):
    """When the submission at `path` was handed in (a Submitted), from what the platform gives: a
    Moodle folder's files keep the time Moodle received them (when unpacked with their times), a
    Canvas file too (its name says `_late_` when Canvas found it late), and a clone (GitHub
    Classroom's) has its last commit, whose date is the student's to set. Never raises."""
    base = unicodedata.normalize('NFC', os.path.basename(os.path.normpath(path)))
    try:
        if os.path.isdir(path):   # the path the teacher gave, followed; nothing inside it is
            if MOODLE_FOLDER.match(base):
                files = [os.path.join(path, n) for n in os.listdir(path)
                         if stat.S_ISREG(os.lstat(os.path.join(path, n)).st_mode)]
                times = [t for t in map(_file_time, files) if t is not None]
                if not times:
                    return Submitted(None, 'the Moodle folder holds no file with Moodle\'s time (%s)'
                                     % KEEP_TIMES, False)
                return Submitted(max(times), 'Moodle\'s download: the time of its files', False)
            if os.path.lexists(os.path.join(path, '.git')):
                return _commit_time(path)
            return Submitted(None, 'a folder without .git or a platform\'s name: no time is known', False)
        canvas = CANVAS_FILE.match(base)
        if canvas:
            marked = ' (Canvas marked it late)' if '_late_' in base.lower() else ''
            when = _file_time(path, follow=True)
            return Submitted(when, 'Canvas\'s download: the time of its file%s' % marked if when
                             else 'Canvas\'s file has not kept Canvas\'s time%s (%s)' % (marked, KEEP_TIMES), False)
        return Submitted(None, 'an archive without a platform\'s name: no time is known', False)
    except OSError as error:
        return Submitted(None, 'its time cannot be read (%s)' % (error.strerror or type(error).__name__), False)


# An archive member to make: its path components, 'file' or 'folder', its size, whether the archive
# gives it an execute bit, and what the archive's reader needs to read it.
Member = collections.namedtuple('Member', 'parts kind size executable source')


def _member_parts(name):
    """The path components of a member's name (NFC; '/' or '\\' between them), or a SubmissionError
    when the name is absolute or climbs with '..'."""
    if name.startswith(('/', '\\')):
        raise SubmissionError('the archive holds %r, an absolute path: refused' % name)
    parts = tuple(part for part in re.split(r'[/\\]', unicodedata.normalize('NFC', name)) if part not in ('', '.'))
    if '..' in parts:
        raise SubmissionError('the archive holds %r, which points outside its folder: refused' % name)
    return parts


def _plan(entries, skipped):
    """The Members to make, checked all together before anything is written. entries: (name, kind,
    size, executable, source), kind 'file', 'folder' or what else the member is (a sentence)."""
    made, kinds, total = [], {}, 0
    for count, (name, kind, size, executable, source) in enumerate(entries, 1):
        if count > MAX_MEMBERS:
            raise SubmissionError('the archive has more than %d files: refused' % MAX_MEMBERS)
        parts = _member_parts(name)
        if kind not in ('file', 'folder'):
            skipped.append('%s (%s)' % (name, kind))
            continue
        if not parts:   # the archive's own top folder ('./')
            if kind == 'file':
                raise SubmissionError('the archive holds a file without a name (%r): refused' % name)
            continue
        if kind == 'file' and kinds.get(parts) == 'file':
            raise SubmissionError('the archive holds %r twice: refused' % '/'.join(parts))
        for depth in range(1, len(parts) + 1):
            wanted = kind if depth == len(parts) else 'folder'
            if kinds.setdefault(parts[:depth], wanted) != wanted:
                raise SubmissionError('the archive holds %r both as a file and as a folder: refused'
                                      % '/'.join(parts[:depth]))
        made.append(Member(parts, kind, max(size, 0), executable, source))
        if kind == 'file':
            total += max(size, 0)
            if total > MAX_UNPACKED_BYTES:
                raise SubmissionError('the archive unpacks to more than %d MB: refused'
                                      % (MAX_UNPACKED_BYTES // 2 ** 20))
    return made


def _what_is(mode):
    """In words, what a file of this st_mode is when it is neither a regular file nor a folder."""
    return {stat.S_IFLNK: 'a link', stat.S_IFIFO: 'a FIFO (named pipe)', stat.S_IFSOCK: 'a socket',
            stat.S_IFCHR: 'a device', stat.S_IFBLK: 'a device'}.get(stat.S_IFMT(mode), 'neither a file nor a folder')


def _open_folder(root, parts):
    """A descriptor of the folder root/parts: each component made a real folder (0o755) when it is
    missing, and opened without following it if it is anything but a folder."""
    folder = os.dup(root)
    try:
        for part in parts:
            try:
                os.mkdir(part, 0o755, dir_fd=folder)
            except FileExistsError:
                pass
            child = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=folder)
            os.close(folder)
            folder = child
            os.fchmod(folder, 0o755)   # whatever the umask
    except BaseException:
        os.close(folder)
        raise
    return folder


def _write(root, members, open_member):
    """Makes each Member under the folder descriptor root; open_member(source) reads its content."""
    for member in members:
        folder = _open_folder(root, member.parts if member.kind == 'folder' else member.parts[:-1])
        try:
            if member.kind == 'file':
                mode = 0o755 if member.executable else 0o644
                fd = os.open(member.parts[-1], os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC,
                             mode, dir_fd=folder)
                with os.fdopen(fd, 'wb') as out, open_member(member.source) as source:
                    os.fchmod(fd, mode)
                    _copy_limited(source, out, member.size)
        finally:
            os.close(folder)


def _copy_limited(source, out, size):
    written = 0
    while True:
        chunk = source.read(1 << 16)
        if not chunk:
            break
        written += len(chunk)
        if written > size:
            raise SubmissionError('an archive member is bigger than it says: refused')
        out.write(chunk)


def _tar_kind(member):
    """'file', 'folder', or what else a tar member is."""
    if member.isfile():
        return 'file'
    if member.isdir():
        return 'folder'
    if member.issym():
        return 'a link to %r' % member.linkname
    if member.islnk():
        return 'a hard link to %r' % member.linkname
    if member.ischr() or member.isblk():
        return 'a device'
    return 'a FIFO (named pipe)' if member.isfifo() else 'neither a file nor a folder'


def _extract_tar(stream, name, root, skipped):
    try:
        tar = tarfile.open(fileobj=stream, mode='r:*')
    except UNREADABLE as error:
        raise SubmissionError('%s is not a readable .tar.gz archive (%s)' % (name, error))
    with tar:
        members = _plan(((member.name, _tar_kind(member), member.size, member.mode & 0o111, member)
                         for member in tar), skipped)
        _write(root, members, tar.extractfile)


def _zip_kind(info):
    """'file', 'folder', or what else the unix mode of a zip entry says it is (a link, a device)."""
    mode = info.external_attr >> 16
    if stat.S_IFMT(mode) not in (0, stat.S_IFREG, stat.S_IFDIR):
        return _what_is(mode)
    return 'folder' if info.filename.endswith('/') else 'file'   # is_dir() fails on an empty name


def _extract_zip(stream, name, root, skipped):
    try:
        zipped = zipfile.ZipFile(stream)
    except UNREADABLE as error:
        raise SubmissionError('%s is not a readable .zip archive (%s)' % (name, error))
    with zipped:
        members = _plan(((info.filename, _zip_kind(info), info.file_size, (info.external_attr >> 16) & 0o111, info)
                         for info in zipped.infolist()), skipped)
        _write(root, members, zipped.open)


def _open_regular(path):
    """path opened for reading, when it is a regular file (opening a FIFO named alice.zip would block)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as error:
        raise SubmissionError('%s cannot be read (%s)' % (os.path.basename(path), error.strerror))
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        raise SubmissionError('%s is %s, not an archive: refused' % (os.path.basename(path), _what_is(mode)))
    return os.fdopen(fd, 'rb')


def check_folder(folder):
    """Refuse a submission folder holding a FIFO, a socket or a device (reading one would block the
    grader, or worse) or a link that leads outside it."""
    folder = os.path.realpath(folder)
    for parent, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(parent, name)
            mode = os.lstat(path).st_mode
            if stat.S_ISLNK(mode):
                target = os.path.realpath(path)
                if target != folder and not target.startswith(folder + os.sep):
                    raise SubmissionError('%s is a link to %s, outside the submission: refused'
                                          % (os.path.relpath(path, folder), os.readlink(path)))
            elif not (stat.S_ISDIR(mode) or stat.S_ISREG(mode)):
                raise SubmissionError('%s is %s, not a file: refused' % (os.path.relpath(path, folder), _what_is(mode)))


def upload_inside(folder):
    """The one archive a platform's folder holds (Moodle keeps a student's upload so), or None when
    the folder itself is the submission (it has a package.xml, or no archive at its top). A link is
    never taken for the archive."""
    for parent, dirs, files in os.walk(folder):
        if 'package.xml' in files:
            return None
    archives = sorted(name for name in os.listdir(folder) if name.endswith(ARCHIVE_SUFFIXES)
                      and not name.startswith('.') and stat.S_ISREG(os.lstat(os.path.join(folder, name)).st_mode))
    if len(archives) > 1:
        raise SubmissionError('the folder holds %d archives and no package.xml (%s): hand in one'
                              % (len(archives), ', '.join(archives)))
    return os.path.join(folder, archives[0]) if archives else None


def unpack(path, destination, skipped=None):
    """The submission's folder: `path` itself if it is a folder, or the one archive it holds, or
    the archive `path` unpacked into destination (which must exist and be empty). The list skipped,
    when given, gets the members not made (links, devices: the module's docstring), as sentences."""
    skipped = [] if skipped is None else skipped
    if os.path.isdir(path):
        check_folder(path)
        inside = upload_inside(path)
        if inside is None:
            return os.path.realpath(path)
        path = inside
    if not os.path.exists(path):
        raise SubmissionError('%s does not exist' % path)
    name = os.path.basename(path)
    if path.endswith('.zip'):
        extract = _extract_zip
    elif path.endswith(('.tar.gz', '.tgz')):
        extract = _extract_tar
    else:
        raise SubmissionError('%s is neither a folder nor a .zip or .tar.gz archive' % name)
    destination = os.path.realpath(destination)
    root = os.open(destination, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        with _open_regular(path) as stream:
            extract(stream, name, root, skipped)
    except UNREADABLE as error:
        raise SubmissionError('%s cannot be unpacked (%s): refused' % (name, error))
    finally:
        os.close(root)
    return destination


def package_name(package_xml):
    """The <name> of a package.xml, or None: also when it is not a regular file (a FIFO would block
    the reader) or is a link (which may lead out of the submission)."""
    try:
        fd = os.open(package_xml, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError:
        return None
    with os.fdopen(fd, 'rb') as stream:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        text = stream.read(200000).decode('utf-8', errors='replace')
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
