"""The hostile upload of issue 31, for the tests that grade archives: a student's package in a
catkin workspace, after the links l1 -> ., l1/l2 -> .., l2/l3 -> .. and before l2/l3/marker.txt,
which an unpacker that writes through links puts two folders above the one it unpacks into."""
import io
import os
import tarfile

LINK_CHAIN = [('l1', '.'), ('l1/l2', '..'), ('l2/l3', '..')]
MARKER = 'marker.txt'


def link_chain_archive(path, package):
    """Writes the .tar.gz `path`: the links, catkin_ws/src/<the folder package>, then the marker.
    Returns path."""
    with tarfile.open(path, 'w:gz') as tar:
        for name, target in LINK_CHAIN:
            link = tarfile.TarInfo(name)
            link.type, link.linkname = tarfile.SYMTYPE, target
            tar.addfile(link)
        tar.add(package, arcname='catkin_ws/src/' + os.path.basename(package))
        marker = tarfile.TarInfo('l2/l3/' + MARKER)
        marker.size = 4
        tar.addfile(marker, io.BytesIO(b'here'))
    return path


def markers_under(*folders):
    """The paths of every marker file under folders (links not followed)."""
    return sorted(os.path.join(parent, MARKER) for folder in folders for parent, _, names in os.walk(folder)
                  if MARKER in names)
