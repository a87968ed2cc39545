"""The labs of the tour: each starts what the course starts, measures what a student would look at,
and returns a few summary lines and the pictures it saved."""
import collections
import math
import time

from course_tour.session import Recorder, path_length

LabReport = collections.namedtuple('LabReport', 'lines pictures')
Lab = collections.namedtuple('Lab', 'name seed title run')


def turtlesim_square(session):
    """turtlesim's draw_square drives turtle1 once round its 2 m square; the canvas is saved."""
    from turtlesim.msg import Pose
    canvas = session.picture('turtlesim-square.png')
    poses = Recorder('/turtle1/pose', Pose)
    launched = session.launch('turtlesim', 'draw_square_demo.launch', canvas_png=canvas)
    start = time.monotonic()

    def square_closed():
        points = [(p.x, p.y) for p in poses.snapshot()]
        return (len(points) > 1 and path_length(points) > 7.8
                and math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1]) < 0.15)

    session.wait_until(square_closed, 90, 'turtle1 to drive round the square')
    seconds = session.elapsed_since(start)
    points = [(p.x, p.y) for p in poses.snapshot()]
    poses.close()
    session.stop(launched)  # the simulator writes the canvas as it shuts down
    gap = math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1])
    return LabReport(['turtle1 drove %.2f m round the square in %.0f s; it closed within %.3f m'
                      % (path_length(points), seconds, gap)], [canvas])


LABS = [
    Lab('square', 'turtlesim', 'turtlesim draws a square (draw_square)', turtlesim_square),
]
