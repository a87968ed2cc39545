"""The README's demo: the tour runs every lab, summarises it, and writes real pictures."""
import os
import re
import signal
import subprocess

import numpy
import pytest
from PIL import Image

from course_common.process_table import command_line, marked_processes, new_mark, stop_marked, with_mark
from course_testing.rviz import UNCOVERED_AT_MOST
from course_testing.screen import red_pixels, uncovered_pixels
from course_common.waiting import wait_until

TURTLESIM_BACKGROUND = (69, 86, 255)
PEN = (179, 184, 255)
RVIZ_ROBOT_BODY = (191, 191, 191)  # fake_tb3's URDF 'light' material, lit from above


def left_running(mark):
    """The command lines of what still runs with `mark` in its environment; stops them."""
    left = [command_line(pid) for pid in marked_processes(mark)]
    stop_marked(mark)
    return left


@pytest.fixture(scope='module')
def tour(tmp_path_factory):
    """The tour's result, its folder, and what it started that still runs once it has ended."""
    output = tmp_path_factory.mktemp('tour')
    mark = new_mark('COURSE_TOUR_TEST')
    try:
        result = subprocess.run(['rosrun', 'course_tour', 'tour', '--output', str(output)],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True, timeout=900, env=with_mark(mark))
    finally:
        left = left_running(mark)
    return result, output, left


def test_nothing_the_tour_started_runs_after_it(tour):
    # roscore, the simulators, the course nodes (roslaunch's, in sessions of their own), Xvfb, rviz.
    assert tour[2] == []


def test_the_tour_killed_in_a_lab_stops_what_it_started(tmp_path):
    mark = new_mark('COURSE_TOUR_TEST')
    tour = subprocess.Popen(['rosrun', 'course_tour', 'tour', 'square', '--output', str(tmp_path)],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                            env=with_mark(mark))
    try:
        wait_until(lambda: any('turtlesim' in command_line(pid) for pid in marked_processes(mark)), 60,
                   'the square lab to start turtlesim')
        tour.terminate()
        output = tour.communicate(timeout=60)[0]
    finally:
        tour.kill()
        left = left_running(mark)
    assert left == []
    assert tour.returncode == 128 + signal.SIGTERM, output


def picture(output, name):
    with Image.open(os.path.join(str(output), name)) as image:
        return numpy.asarray(image.convert('RGB')).astype(int)


def pixels_of(image, colour):
    return int(numpy.all(image == colour, axis=2).sum())


def test_every_lab_ran_and_the_tour_says_where_its_pictures_are(tour):
    result, output, _ = tour
    assert result.returncode == 0, result.stdout
    for number, lab in enumerate(['square', 'turtle', 'teleop', 'report', 'laser', 'avoid', 'rviz'], 1):
        assert re.search(r'^\[%d/7\] %s: .* \.\.\.$' % (number, lab), result.stdout, re.M)
    assert 'FAILED' not in result.stdout
    assert result.stdout.rstrip().endswith('Pictures and logs are in %s' % output)


def test_the_summary_gives_distances_stop_distance_and_no_collision(tour):
    summary = tour[0].stdout.split('\nSummary\n')[1]
    driven = float(re.search(r'turtle1 drove ([\d.]+) m along \+x', summary).group(1))
    assert driven >= 2.0
    assert re.search(r'my_turtle_pose printed (\d+) pose lines', summary)
    assert re.search(r'square of 3 m sides: 12\.\d\d m driven, closed within 0\.0[0-4]\d m', summary)
    assert re.search(r'triangle of 3 m sides: 9\.\d\d m driven, closed within 0\.0[0-4]\d m', summary)
    stop = float(re.search(r'stopped ([\d.]+) m from the wall \(front beam, median over the stop\); collisions: 0',
                           summary).group(1))
    assert 0.35 <= stop <= 0.5
    wandered = float(re.search(r'wander.py drove ([\d.]+) m in 120 simulated seconds .*; collisions: 0',
                               summary).group(1))
    assert wandered > 10.0
    assert re.search(r'laser_data printed \d+ scans; the last: front \S+', summary)


@pytest.mark.parametrize('name', ['turtlesim-square.png', 'my_turtle-forward.png', 'my_turtle-teleop.png',
                                  'ros_exercises-square.png', 'ros_exercises-triangle.png'])
def test_turtle_canvases_are_500_px_squares_with_a_trail(tour, name):
    image = picture(tour[1], name)
    assert image.shape == (500, 500, 3)
    assert pixels_of(image, TURTLESIM_BACKGROUND) > 0.9 * 500 * 500
    assert pixels_of(image, PEN) > 200  # a 3 px pen over more than a metre (45 px/m)


@pytest.mark.parametrize('name', ['ros_exercises-square.png', 'ros_exercises-triangle.png'])
def test_the_report_shapes_show_the_turtle_that_drew_them(tour, name):
    image = picture(tour[1], name)
    # The turtle icon (about 22 px square, its colours vary with the icon) is all that is
    # neither the background nor the pen.
    turtle = image.shape[0] * image.shape[1] - pixels_of(image, TURTLESIM_BACKGROUND) - pixels_of(image, PEN)
    assert turtle > 200


def test_the_top_down_view_shows_the_world_and_a_long_trail(tour):
    image = picture(tour[1], 'move_turtlebot3-wander.png')
    assert image.shape[0] > 300 and image.shape[1] > 300
    colours = {tuple(c) for c in image.reshape(-1, 3)[::97]}
    assert len(colours) > 4  # floor, walls, trail, robot, scan
    trail = (image[:, :, 2] > 150) & (image[:, :, 0] < 120)  # blue
    assert trail.sum() > 300
    assert red_pixels(os.path.join(str(tour[1]), 'move_turtlebot3-wander.png')) > 50  # the scan


def test_the_rviz_screenshot_shows_red_laser_points(tour):
    assert picture(tour[1], 'rviz.png').shape == (1024, 1280, 3)
    assert red_pixels(os.path.join(str(tour[1]), 'rviz.png')) > 300


def test_the_rviz_window_fills_the_screen_and_shows_the_robot(tour):
    image = picture(tour[1], 'rviz.png')
    uncovered, where = uncovered_pixels(os.path.join(str(tour[1]), 'rviz.png'))
    assert uncovered <= UNCOVERED_AT_MOST * 1280 * 1024, where  # no black bands round the window
    assert pixels_of(image, RVIZ_ROBOT_BODY) > 400  # the body, over 20 px square
