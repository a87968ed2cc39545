"""The scenes the page draws, rebuilt from what the simulators publish, and the frames each page
gets (pure, milliseconds)."""
import base64
import json
import math
import zlib

import numpy as np
import pytest

from course_web.frames import NEW_PAGE, Scenes
from course_web.tb3_scene import MAX_TRAIL_POINTS, Tb3Scene, scan_points
from course_web.turtlesim_scene import MAX_PENDING_OPS, SceneError, TurtlesimScene
from fake_tb3.world import load_world
from turtlesim.canvas import Canvas


class Quiet:
    def info(self, text):
        pass

    def warning(self, text):
        pass


def canvas_message(canvas, seq, turtles=(), ops=()):
    pixels = canvas.pixels
    return {'seq': seq, 'stamp': 1.0, 'ops': list(ops), 'turtles': [list(t) for t in turtles],
            'canvas': {'height': pixels.shape[0], 'width': pixels.shape[1],
                       'rgb_zlib_base64': base64.b64encode(zlib.compress(pixels.tobytes())).decode()}}


def test_lines_and_fills_give_turtlesims_own_pixels():
    original = Canvas((69, 86, 255))
    original.draw_line(10, 10, 200, 120, (179, 184, 255), 3)
    scene = TurtlesimScene()
    assert scene.apply(canvas_message(original, 1, [('turtle1', 5.5, 5.5, 0.0, 2)]))
    ops = [['line', 100.0, 400.0, 300.5, 250.25, 255, 0, 0, 5], ['line', 50, 50, 50, 50, 0, 255, 0, 1]]
    for op in ops:
        original.draw_line(*op[1:5], tuple(op[5:8]), op[8])
    assert scene.apply({'seq': 2, 'stamp': 2.0, 'ops': ops, 'turtles': [['turtle1', 6.0, 5.5, 0.1, 2]]})
    assert np.array_equal(scene.pixels(), original.pixels)
    assert list(scene.turtles.values()) == [['turtle1', 6.0, 5.5, 0.1, 2]]
    original.fill((10, 20, 30))
    assert scene.apply({'seq': 3, 'stamp': 3.0, 'ops': [['fill', 10, 20, 30]], 'turtles': []})
    assert np.array_equal(scene.pixels(), original.pixels)


def test_a_missed_message_is_noticed_and_the_next_picture_repairs_it():
    canvas = Canvas((69, 86, 255))
    scene = TurtlesimScene()
    assert not scene.apply({'seq': 5, 'stamp': 0.0, 'ops': [], 'turtles': []})  # no picture yet
    assert scene.apply(canvas_message(canvas, 5))
    generation = scene.generation
    assert not scene.apply({'seq': 7, 'stamp': 0.0, 'ops': [['fill', 0, 0, 0]], 'turtles': []})
    assert scene.op_count == 0
    assert scene.apply(canvas_message(canvas, 9))
    assert scene.generation == generation + 1


@pytest.mark.parametrize('bad', [
    {'seq': 2, 'stamp': 0.0, 'ops': [['circle', 1, 2]], 'turtles': []},
    {'seq': 2, 'stamp': 0.0, 'ops': [['fill', 300, 0, 0]], 'turtles': []},
    {'seq': 2, 'stamp': 0.0, 'ops': [['line', 'a', 0, 0, 0, 0, 0, 0, 1]], 'turtles': []},
    {'seq': 2, 'stamp': 0.0, 'ops': [], 'turtles': [['turtle1', 1.0]]},
    {'seq': 2, 'stamp': 0.0, 'ops': [], 'turtles': [], 'gone': [1]},
    {'seq': 2, 'stamp': 0.0, 'ops': []},
])
def test_malformed_scene_messages_are_errors(bad):
    scene = TurtlesimScene()
    scene.apply(canvas_message(Canvas((0, 0, 0)), 1))
    with pytest.raises(SceneError):
        scene.apply(bad)


def test_a_huge_canvas_is_refused():
    scene = TurtlesimScene()
    with pytest.raises(SceneError, match='canvas of'):
        scene.apply({'seq': 1, 'stamp': 0.0, 'ops': [], 'turtles': [],
                     'canvas': {'height': 100000, 'width': 100000, 'rgb_zlib_base64': ''}})


def test_pages_get_everything_once_then_only_what_changed():
    scenes = Scenes()
    canvas = Canvas((69, 86, 255))
    scenes.turtlesim.apply(canvas_message(canvas, 1, [('turtle1', 5.5, 5.5, 0.0, 0)]))
    text, cursor = scenes.frame_for(NEW_PAGE)
    first = json.loads(text)
    assert first['turtlesim']['canvas'].startswith('data:image/png;base64,')
    assert first['tb3'] == {'present': False}
    assert scenes.frame_for(cursor) == (None, cursor)  # nothing new
    assert scenes.frame_for(NEW_PAGE)[0] is text  # a second new page: the same text, made once
    message = scenes.message_for(NEW_PAGE)[0]  # and the same websocket message
    assert message is scenes.message_for(NEW_PAGE)[0] and message.endswith(text.encode())
    assert scenes.message_for(cursor) == (None, cursor)
    scenes.turtlesim.apply({'seq': 2, 'stamp': 2.0, 'ops': [['line', 1, 2, 3, 4, 5, 6, 7, 2]],
                            'turtles': [['turtle1', 5.6, 5.5, 0.0, 0]]})
    text, cursor = scenes.frame_for(cursor)
    update = json.loads(text)
    assert 'canvas' not in update['turtlesim'] and 'tb3' not in update
    assert update['turtlesim']['ops'] == [['line', 1, 2, 3, 4, 5, 6, 7, 2]]
    scenes.turtlesim.vanish()
    text, cursor = scenes.frame_for(cursor)
    assert json.loads(text) == {'turtlesim': {'present': False}}


def test_a_page_one_frame_behind_gets_only_the_turtles_that_changed():
    scenes = Scenes()
    turtles = [('turtle1', 5.5, 5.5, 0.0, 0), ('turtle2', 1.0, 1.0, 0.0, 3), ('turtle3', 2.0, 2.0, 0.0, 1)]
    scenes.turtlesim.apply(canvas_message(Canvas((0, 0, 0)), 1, turtles))
    _, cursor = scenes.frame_for(NEW_PAGE)
    _, behind = scenes.frame_for(NEW_PAGE)
    scenes.turtlesim.apply({'seq': 2, 'stamp': 0.0, 'ops': [], 'turtles': [['turtle1', 5.6, 5.5, 0.0, 0]]})
    text, cursor = scenes.frame_for(cursor)
    part = json.loads(text)['turtlesim']
    assert part['turtles'] == [['turtle1', 5.6, 5.5, 0.0, 0]] and part['gone'] == [] and 'all' not in part
    scenes.turtlesim.apply({'seq': 3, 'stamp': 0.0, 'ops': [], 'turtles': [['turtle4', 3.0, 3.0, 1.0, 2]],
                            'gone': ['turtle2']})
    part = json.loads(scenes.frame_for(cursor)[0])['turtlesim']
    assert part['turtles'] == [['turtle4', 3.0, 3.0, 1.0, 2]] and part['gone'] == ['turtle2']
    # A page two messages behind gets every turtle as they are now.
    part = json.loads(scenes.frame_for(behind)[0])['turtlesim']
    assert part['all'] and part['turtles'] == [['turtle1', 5.6, 5.5, 0.0, 0], ['turtle3', 2.0, 2.0, 0.0, 1],
                                               ['turtle4', 3.0, 3.0, 1.0, 2]]


def test_a_page_far_behind_gets_a_new_picture_instead_of_every_line():
    scenes = Scenes()
    scenes.turtlesim.apply(canvas_message(Canvas((0, 0, 0)), 1))
    _, cursor = scenes.frame_for(NEW_PAGE)
    for seq in range(2, MAX_PENDING_OPS + 100):
        scenes.turtlesim.apply({'seq': seq, 'stamp': 0.0, 'ops': [['line', 0, 0, 1, 1, 9, 9, 9, 1]],
                                'turtles': []})
    part = json.loads(scenes.frame_for(cursor)[0])['turtlesim']
    assert 'canvas' in part and part['ops'] == []


def test_scan_points_are_where_the_beams_end():
    points, closest = scan_points(1.0, 2.0, math.pi / 2, (-0.032, 0.0), [1.0, math.inf, 0.05, 2.0],
                                  0.0, math.pi / 2, 0.12, 3.5)
    # the laser sits 0.032 m behind the centre: at (1.0, 1.968), facing +y
    assert points == [[1.0, 2.968], [3.0, 1.968]]  # beam 3: 3 pi / 2 + yaw pi / 2 is +x
    assert closest == 1.0


def test_the_robot_its_path_and_its_world():
    scene = Tb3Scene()
    scene.start(load_world('turtlebot3_world'), 'burger')
    assert scene.world['name'] == 'turtlebot3_world'
    pillars = [data for kind, data in scene.world['shapes'] if kind == 'circle']
    assert [-1.1, -1.1, 0.15] in pillars and len(pillars) == 9
    for step in range(100):
        scene.on_odom(-2.0 + step * 0.002, -0.5, 0.0, 0.1, 0.0)
    assert len(scene.trail) == 20  # a point every centimetre
    scene.on_odom(float('nan'), 0.0, 0.0, 0.0, 0.0)
    assert scene.pose == (-2.0 + 99 * 0.002, -0.5, 0.0)
    scene.on_scan([1.0] * 360, 0.0, 6.28319 / 359, 0.12, 3.5)
    assert len(scene.scan) == 360 and scene.closest == 1.0


def test_a_long_path_keeps_its_newest_half():
    scene = Tb3Scene()
    scene.start(load_world('empty'), 'waffle')
    for step in range(MAX_TRAIL_POINTS + 1):
        scene.on_odom(step * 0.02, 0.0, 0.0, 0.0, 0.0)
    assert len(scene.trail) <= MAX_TRAIL_POINTS and scene.trail[-1] == [round(MAX_TRAIL_POINTS * 0.02, 3), 0.0]
    assert scene.trail_since(0) is None and scene.trail_since(scene.trail_end) == []
