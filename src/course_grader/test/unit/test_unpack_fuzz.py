"""Thousands of generated hostile archives unpacked (seeded, the same every run): nothing outside the
unpacking folder changes, nothing inside it is a link, a device or a FIFO, and every refusal is a
SubmissionError (no ROS)."""
import gzip
import io
import os
import random
import shutil
import stat
import tarfile
import zipfile

import pytest

from course_grader import submission
from course_grader.submission import SubmissionError

CASES = 1000   # per archive format
# Path components the names are made of: links made earlier in the same archive, '.', empty ones,
# the same word in NFC and NFD, control characters; now and then one that climbs.
COMPONENTS = ['a', 'b', 'l1', 'l2', 'l3', '.', '', 'caf\u00e9', 'cafe\u0301', 'x\ny', 'package.xml']
CLIMBING = ['..', 'd\\..\\e']
LINK_TARGETS = ['.', '..', '../..', '../../..', 'a', 'l1', 'l1/l2', '../neighbour.txt', '/', '/etc', '/etc/passwd']
DEVICE_TYPES = [tarfile.CHRTYPE, tarfile.BLKTYPE, tarfile.FIFOTYPE, b'Z']   # b'Z': a type tarfile does not know
ZIP_TYPES = [stat.S_IFLNK, stat.S_IFCHR, stat.S_IFBLK, stat.S_IFIFO, stat.S_IFSOCK, stat.S_IFDIR, stat.S_IFREG, 0]


@pytest.fixture
def world(tmp_path):
    """A canary tree around the unpacking folder box/target: files and folders beside it, above it,
    and a folder reach/ that absolute links and names point into."""
    world = tmp_path / 'world'
    (world / 'reach' / 'sub').mkdir(parents=True)
    (world / 'box' / 'target').mkdir(parents=True)
    (world / 'reach' / 'inside.txt').write_text('canary')
    (world / 'box' / 'neighbour.txt').write_text('neighbour')
    (world / 'sibling.sh').write_text('#!/bin/sh\n')
    (world / 'sibling.sh').chmod(0o755)
    (world / '.hidden').write_bytes(b'\0\1')
    os.symlink('reach', str(world / 'to_reach'))
    return world


def snapshot(world):
    """Everything in world but the unpacking folder, and the names beside world: path, mode, content."""
    seen = {'..': sorted(os.listdir(str(world.parent)))}
    for parent, dirs, files in os.walk(str(world)):
        dirs[:] = [d for d in dirs if os.path.join(parent, d) != str(world / 'box' / 'target')]
        for name in dirs + files:
            path = os.path.join(parent, name)
            mode = os.lstat(path).st_mode
            if stat.S_ISLNK(mode):
                content = os.readlink(path)
            elif stat.S_ISREG(mode):
                with open(path, 'rb') as stream:
                    content = stream.read()
            else:
                content = None
            seen[os.path.relpath(path, str(world))] = (mode, content)
    return seen


def strange_entries(target):
    """What in the unpacked folder is not a regular file (0o644, 0o755) or a folder (0o755)."""
    found = []
    for parent, dirs, files in os.walk(target):
        for name in dirs + files:
            path = os.path.join(parent, name)
            mode = os.lstat(path).st_mode
            if not ((stat.S_ISDIR(mode) and stat.S_IMODE(mode) == 0o755)
                    or (stat.S_ISREG(mode) and stat.S_IMODE(mode) in (0o644, 0o755))):
                found.append((os.path.relpath(path, target), oct(mode)))
    return found


def random_name(rng, world):
    if rng.random() < 0.02:   # absolute: into the canary's reach/, or the root
        return rng.choice([str(world / 'reach' / 'written.txt'), '/' + rng.choice(COMPONENTS), '\\evil'])
    return '/'.join(rng.choice(CLIMBING if rng.random() < 0.04 else COMPONENTS) for _ in range(rng.randint(1, 4)))


def random_members(rng, world):
    """(kind, name, argument) of a random archive: a chain of links written through, a bomb, or a mix."""
    shape = rng.random()
    if shape < 0.15:   # links first, then files through them, as in issue 31
        links = [('symlink', name, rng.choice(LINK_TARGETS + [str(world / 'reach')]))
                 for name in ('l1', 'l1/l2', 'l2/l3', 'a')]
        rng.shuffle(links)
        through = rng.choice(['l1/x.txt', 'l2/l3/marker.txt', 'l1/l2/l3/y', 'a/inside.txt'])
        return links + [('file', through, b'through')]
    if shape < 0.20:   # a bomb: more members than allowed (the limit is lowered for the test)
        return [('file', 'm%d' % index, b'') for index in range(rng.choice([40, 41, 60]))]
    if shape < 0.25:   # a bomb: bigger than allowed, or a size that lies
        return [('file', 'big%d' % index, b'\0' * rng.choice([1000, 3000])) for index in range(3)] + \
            [('liar', 'liar', (b'x' * 100, rng.choice([0, 50, 99, 101, 5000, 10 ** 9])))]
    members = []
    for _ in range(rng.randint(1, 8)):
        kind = rng.choice(['file', 'file', 'folder', 'symlink', 'symlink', 'hardlink', 'device', 'nested', 'liar'])
        name = random_name(rng, world)
        argument = {'file': lambda: rng.choice([b'', b'data', b'#!/bin/sh\n']),
                    'folder': lambda: None,
                    'symlink': lambda: rng.choice(LINK_TARGETS + [str(world / 'reach'), str(world)]),
                    'hardlink': lambda: rng.choice(['../neighbour.txt', str(world / 'reach' / 'inside.txt'), 'a',
                                                    'l1/x']),
                    'device': lambda: rng.choice(DEVICE_TYPES if rng.random() < 0.5 else ZIP_TYPES),
                    'nested': lambda: make_tar([('file', 'inner/../../x', b'x')]),
                    'liar': lambda: (b'y' * 10, rng.choice([0, 5, 11, 10 ** 6]))}[kind]()
        members.append((kind, name, argument))
    return members


def loose_mode(index):
    """Every other member asks for setuid, setgid and write for all; the others for no execute bit."""
    return 0o6777 if index % 2 else 0o600


def tar_info(kind, name, argument, mode):
    """The TarInfo and content of a member."""
    info = tarfile.TarInfo(name)
    info.mode = mode
    content = None
    if kind in ('file', 'nested'):
        content = argument
    elif kind == 'folder':
        info.type = tarfile.DIRTYPE
    elif kind == 'symlink':
        info.type, info.linkname = tarfile.SYMTYPE, argument
    elif kind == 'hardlink':
        info.type, info.linkname = tarfile.LNKTYPE, argument
    elif kind == 'device':
        info.type = argument if isinstance(argument, bytes) else tarfile.CHRTYPE
    else:   # a liar: the data, then the size its header gives (patched in after)
        content = argument[0]
    if content is not None:
        info.size = len(content)
    return info, content


def make_tar(members, tar_format=tarfile.GNU_FORMAT):
    """The bytes of a .tar.gz holding members; a liar's header gives another size than its data."""
    raw = io.BytesIO()
    lies = []
    with tarfile.open(fileobj=raw, mode='w', format=tar_format) as tar:
        for index, (kind, name, argument) in enumerate(members):
            info, content = tar_info(kind, name, argument, loose_mode(index))
            tar.addfile(info, io.BytesIO(content) if content is not None else None)
            if kind == 'liar':   # its own header: the block before its data (a long name's come before)
                lies.append((raw.tell() - 512 - -(-len(content) // 512) * 512, argument[1]))
    data = bytearray(raw.getvalue())
    for header, size in lies:   # the size field, then the checksum
        data[header + 124:header + 136] = ('%011o\0' % size).encode()
        data[header + 148:header + 156] = b' ' * 8
        data[header + 148:header + 156] = ('%06o\0 ' % sum(data[header:header + 512])).encode()
    return gzip.compress(bytes(data), mtime=0)


def make_zip(members):
    """The bytes of a .zip holding members, links and devices marked so in their unix mode; a
    liar's size in the central directory is not its data's."""
    raw = io.BytesIO()
    with zipfile.ZipFile(raw, 'w', zipfile.ZIP_DEFLATED) as zipped:
        for index, (kind, name, argument) in enumerate(members):
            info = zipfile.ZipInfo(name.rstrip('/') + '/' if kind == 'folder' else name)
            info.create_system = 3
            content = b''
            if kind in ('file', 'nested'):
                info.external_attr = (stat.S_IFREG | loose_mode(index)) << 16
                content = argument
            elif kind in ('symlink', 'hardlink'):
                info.external_attr = (stat.S_IFLNK | 0o777) << 16
                content = argument.encode()
            elif kind == 'device':
                info.external_attr = ((argument if isinstance(argument, int) else stat.S_IFIFO) | 0o644) << 16
            elif kind == 'liar':
                content = argument[0]
            zipped.writestr(info, content)
            if kind == 'liar':   # the central directory gives another size than the data
                zipped.infolist()[-1].file_size = argument[1]
    return raw.getvalue()


def damaged(rng, data):
    """data, sometimes cut short or with a byte changed."""
    chance = rng.random()
    if chance < 0.05:
        return data[:rng.randrange(len(data))]
    if chance < 0.10:
        position = rng.randrange(len(data))
        return data[:position] + bytes([data[position] ^ (1 << rng.randrange(8))]) + data[position + 1:]
    return data


def unpack_and_check(archive, target, world, before, what):
    """Unpacks archive into target; asserts nothing outside changed and nothing strange is inside."""
    try:
        submission.unpack(archive, str(target))
    except SubmissionError:
        pass
    except Exception as error:   # any other exception would stop the class's grading
        pytest.fail('%s raised %r, not a SubmissionError' % (what, error))
    assert strange_entries(str(target)) == [], what
    assert snapshot(world) == before, what
    if os.listdir(str(target)):
        shutil.rmtree(str(target))
        target.mkdir()


@pytest.fixture
def small_limits(monkeypatch):
    monkeypatch.setattr(submission, 'MAX_MEMBERS', 40)
    monkeypatch.setattr(submission, 'MAX_UNPACKED_BYTES', 5000)


@pytest.mark.filterwarnings('ignore:Duplicate name')   # zipfile's, as it writes a name twice
@pytest.mark.parametrize('suffix', ['.tar.gz', '.zip'])
def test_generated_hostile_archives_change_nothing_outside(world, tmp_path_factory, small_limits, suffix):
    rng = random.Random(31)   # the issue's number: the same archives every run
    archive = str(tmp_path_factory.mktemp('archives') / ('mallory' + suffix))
    target = world / 'box' / 'target'
    before = snapshot(world)
    for case in range(CASES):
        members = random_members(rng, world)
        if suffix == '.zip':
            data = make_zip(members)
        else:
            data = make_tar(members, rng.choice([tarfile.GNU_FORMAT, tarfile.PAX_FORMAT]))
        with open(archive, 'wb') as stream:
            stream.write(damaged(rng, data))
        unpack_and_check(archive, target, world, before, 'case %d: %r' % (case, members))


def test_the_link_chain_of_issue_31_writes_nothing_outside(world, tmp_path_factory):
    """l1 -> ., l1/l2 -> .., l2/l3 -> .., then l2/l3/marker.txt: once written above the unpacking folder."""
    archive = str(tmp_path_factory.mktemp('archives') / 'chain.tar.gz')
    with open(archive, 'wb') as stream:
        stream.write(make_tar([('symlink', 'l1', '.'), ('symlink', 'l1/l2', '..'), ('symlink', 'l2/l3', '..'),
                               ('file', 'l2/l3/marker.txt', b'here')]))
    target = world / 'box' / 'target'
    before = snapshot(world)
    skipped = []
    submission.unpack(archive, str(target), skipped)
    assert snapshot(world) == before
    assert [str(path.relative_to(world.parent)) for path in world.parent.rglob('marker.txt')] == \
        ['world/box/target/l2/l3/marker.txt']
    assert strange_entries(str(target)) == []
    assert skipped == ["l1 (a link to '.')", "l1/l2 (a link to '..')", "l2/l3 (a link to '..')"]
