"""The generated interfaces are the originals' (same md5 sums), so course code cannot tell them apart."""
import pytest

from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

ORIGINAL_MD5 = [
    (Pose, '863b248d5016ca62ea2e895ae5265cf9'),
    (Color, '353891e354491c51aabe32df673fb446'),
    (Spawn, '0b2d2e872a8e2887d5ed626f2bf2c561'),
    (Kill, 'c1f3d28f1b044c871e6eff2e9fc3c667'),
    (SetPen, '9f452acce566bf0c0954594f69a8e41b'),
    (TeleportAbsolute, 'a130bc60ee6513855dc62ea83fcc5b20'),
    (TeleportRelative, '9d5c2dcd348ac8f76ce2a4307bd63a13'),
]


@pytest.mark.parametrize('interface, md5', ORIGINAL_MD5, ids=lambda v: getattr(v, '_type', v))
def test_md5_matches_ros1_turtlesim(interface, md5):
    assert interface._md5sum == md5
