"""Top-down pictures of a simulation: world, robots, their trails and latest scans."""
import numpy as np
from PIL import Image, ImageDraw

from fake_tb3.geometry import box_outline

FLOOR = (250, 250, 250)
GRID = (225, 225, 225)
OBSTACLE = (110, 110, 110)
SCAN = (230, 20, 20)
ROBOT_COLOURS = [(30, 90, 200), (20, 150, 60), (200, 120, 0), (140, 40, 170)]
MARGIN = 0.5          # metres around what is drawn
EMPTY_HALF_SIZE = 2.0  # metres shown around the robots in a world without obstacles


def _view_bounds(simulation):
    xs, ys = [], []
    bounds = simulation.world.bounds()
    if bounds:
        xs += [bounds[0], bounds[2]]
        ys += [bounds[1], bounds[3]]
    for robot in simulation.robots:
        trail = np.array(robot.trail + [(robot.x, robot.y)])
        xs += [trail[:, 0].min() - EMPTY_HALF_SIZE * (not bounds),
               trail[:, 0].max() + EMPTY_HALF_SIZE * (not bounds)]
        ys += [trail[:, 1].min() - EMPTY_HALF_SIZE * (not bounds),
               trail[:, 1].max() + EMPTY_HALF_SIZE * (not bounds)]
    return min(xs) - MARGIN, min(ys) - MARGIN, max(xs) + MARGIN, max(ys) + MARGIN


def render(simulation, pixels_per_metre=100, max_pixels=2000):
    """A PIL image of the simulation seen from above, +x to the right and +y up.

    Obstacles grey on a light floor with a 1 m grid, each robot's body outline and heading in its
    colour, its trail as a thin line, and its latest scan as red dots.
    """
    xmin, ymin, xmax, ymax = _view_bounds(simulation)
    scale = min(pixels_per_metre, max_pixels / max(xmax - xmin, ymax - ymin))
    width, height = int((xmax - xmin) * scale) + 1, int((ymax - ymin) * scale) + 1
    image = Image.new('RGB', (width, height), FLOOR)
    draw = ImageDraw.Draw(image)

    def pixel(x, y):
        return (x - xmin) * scale, (ymax - y) * scale

    for gx in range(int(np.ceil(xmin)), int(np.floor(xmax)) + 1):
        draw.line([pixel(gx, ymin), pixel(gx, ymax)], fill=GRID)
    for gy in range(int(np.ceil(ymin)), int(np.floor(ymax)) + 1):
        draw.line([pixel(xmin, gy), pixel(xmax, gy)], fill=GRID)
    for kind, data in simulation.world.shapes:
        if kind == 'circle':
            cx, cy, r = data
            draw.ellipse([pixel(cx - r, cy + r), pixel(cx + r, cy - r)], fill=OBSTACLE)
        else:
            draw.polygon([pixel(x, y) for x, y in data],
                         fill=OBSTACLE if kind == 'polygon' else FLOOR)
    for index, robot in enumerate(simulation.robots):
        colour = ROBOT_COLOURS[index % len(ROBOT_COLOURS)]
        trail = robot.trail + [(robot.x, robot.y)]
        if len(trail) > 1:
            draw.line([pixel(x, y) for x, y in trail], fill=colour, width=1)
        if robot.last_scan is not None:
            laser_x, laser_y, laser_yaw, ranges = robot.last_scan
            angles = laser_yaw + robot.laser.spec.beam_angles
            seen = np.isfinite(ranges)
            for x, y in zip(laser_x + ranges[seen] * np.cos(angles[seen]),
                            laser_y + ranges[seen] * np.sin(angles[seen])):
                px, py = pixel(x, y)
                draw.ellipse([px - 1.5, py - 1.5, px + 1.5, py + 1.5], fill=SCAN)
        corners = box_outline(robot.x, robot.y, robot.yaw, robot.box)[:, :2]
        draw.polygon([pixel(x, y) for x, y in corners], outline=colour, width=2)
        nose = robot.box[0] + robot.box[1]
        draw.line([pixel(robot.x, robot.y),
                   pixel(robot.x + nose * np.cos(robot.yaw), robot.y + nose * np.sin(robot.yaw))],
                  fill=colour, width=2)
    return image


def save_picture(simulation, path):
    """Write the top-down PNG to path."""
    render(simulation).save(path, format='PNG')
