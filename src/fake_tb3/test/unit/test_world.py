"""World files: the TurtleBot3 world's geometry and clear errors for bad files."""
import pytest

from fake_tb3.world import WorldError, World, available_worlds, load_world


def test_shipped_worlds():
    assert {'empty', 'turtlebot3_world', 'corridor', 'wall_ahead'} <= set(available_worlds())
    assert load_world('empty').bounds() is None


def test_turtlebot3_world_geometry():
    world = load_world('turtlebot3_world')
    pillars = sorted(map(tuple, world.circles.round(6).tolist()))
    assert pillars == sorted((x, y, 0.15) for x in (-1.1, 0.0, 1.1) for y in (-1.1, 0.0, 1.1))
    corners = {tuple(p) for p in world.segments[:, :2].round(4).tolist()}
    # Inner wall corners on the x axis and at (+-1.4665, +-2.54); outer apothem 2.8575.
    assert {(2.9329, 0.0), (-2.9329, 0.0), (1.4665, 2.54), (-1.4665, -2.54)} <= corners
    # Outer circumradius 3.2996: the inner 2.9329 plus the thickness 0.3175 / cos 30.
    assert -min(x for x, y in corners if y == 0.0) == pytest.approx(3.2996, abs=1e-4)
    # Big prism at (3.5, 0), circumradius 1.1732: its corner on the axis at x = 2.3268.
    assert (2.3268, 0.0) in corners
    # Small prisms circumradius 0.8066 at (+-1.8, +-2.7).
    assert {(0.9934, 2.7), (-0.9934, -2.7), (2.6066, -2.7)} <= corners
    assert world.segments.shape == (6 + 6 + 5 * 6, 4)


@pytest.mark.parametrize('obstacle, message', [
    ({'type': 'triangle'}, "unknown obstacle type 'triangle'"),
    ({'type': 'circle', 'center': [0, 0]}, "missing key 'radius'"),
    ({'type': 'circle', 'center': [0, 0], 'radius': -1}, 'radius must be positive'),
    ({'type': 'polygon', 'points': [[0, 0], [1, 0]]}, 'at least 3 points'),
    ({'type': 'box', 'center': 'here', 'size': [1, 1]}, 'obstacle 1'),
])
def test_bad_obstacles_are_named(obstacle, message):
    with pytest.raises(WorldError, match=message):
        World('bad', [obstacle])


def test_bad_files(tmp_path):
    with pytest.raises(WorldError,
                       match="no world 'moon': give a YAML file or one of .*turtlebot3_world"):
        load_world('moon')
    broken = tmp_path / 'broken.yaml'
    broken.write_text('obstacles: [unclosed\n')
    with pytest.raises(WorldError, match='cannot read world file'):
        load_world(str(broken))
    wrong = tmp_path / 'wrong.yaml'
    wrong.write_text('obstacles: 3\n')
    with pytest.raises(WorldError, match='a list `obstacles`'):
        load_world(str(wrong))
    good = tmp_path / 'mine.yaml'
    good.write_text('obstacles:\n  - {type: circle, center: [1, 2], radius: 0.5}\n')
    assert load_world(str(good)).name == 'mine'
