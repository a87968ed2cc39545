"""A URDF of a TurtleBot3 model in simple shapes (boxes and cylinders), from the model's numbers.

The frames and joints are those of turtlebot3_description: base_footprint -> base_link (z 0.010)
-> wheels, casters, imu_link, base_scan (and camera_link on the waffles). Every link name gets
`prefix` (e.g. 'tb3_0/') for robots sharing one TF tree; joint names stay as joint_states names
them.
"""
from fake_tb3.models import BASE_LINK_HEIGHT, UnknownModelError, get_model

WHEEL_HEIGHT = 0.023
WHEEL_WIDTH = 0.018
LASER_RADIUS = 0.035
LASER_HEIGHT = 0.04
COLOURS = {'dark': '0.2 0.2 0.2 1', 'light': '0.75 0.75 0.75 1', 'blue': '0.1 0.3 0.8 1'}


def _xyz(values):
    return ' '.join('%.7g' % v for v in values)


def _link(name, shape=None, origin=(0, 0, 0), rpy=(0, 0, 0), colour='dark'):
    if shape is None:
        return '  <link name="%s"/>\n' % name
    return ('  <link name="%s">\n    <visual>\n      <origin xyz="%s" rpy="%s"/>\n'
            '      <geometry>%s</geometry>\n      <material name="%s"/>\n    </visual>\n  </link>\n'
            % (name, _xyz(origin), _xyz(rpy), shape, colour))


def _joint(name, kind, parent, child, origin, rpy=(0, 0, 0)):
    axis = '\n    <axis xyz="0 0 1"/>' if kind == 'continuous' else ''
    return ('  <joint name="%s" type="%s">\n    <parent link="%s"/>\n    <child link="%s"/>\n'
            '    <origin xyz="%s" rpy="%s"/>%s\n  </joint>\n'
            % (name, kind, parent, child, _xyz(origin), _xyz(rpy), axis))


def turtlebot3_urdf(model, prefix=''):
    """The URDF (XML text) of `model` (a RobotModel)."""
    link = lambda name: prefix + name  # noqa: E731
    parts = ['<?xml version="1.0"?>\n<robot name="turtlebot3_%s">\n' % model.name]
    parts += ['  <material name="%s"><color rgba="%s"/></material>\n' % item
              for item in COLOURS.items()]
    parts.append(_link(link('base_footprint')))
    parts.append(_joint('base_joint', 'fixed', link('base_footprint'), link('base_link'),
                        (0, 0, BASE_LINK_HEIGHT)))
    parts.append(_link(link('base_link'), '<box size="%s"/>' % _xyz(
        (model.body_length, model.body_width, model.body_height)),
        (model.body_offset_x, 0, model.body_centre_z), colour='light'))
    wheel = '<cylinder radius="%g" length="%g"/>' % (model.wheel_radius, WHEEL_WIDTH)
    for side, y in (('left', model.wheel_offset_y), ('right', -model.wheel_offset_y)):
        parts.append(_joint('wheel_%s_joint' % side, 'continuous', link('base_link'),
                            link('wheel_%s_link' % side), (0, y, WHEEL_HEIGHT), (-1.5707963, 0, 0)))
        parts.append(_link(link('wheel_%s_link' % side), wheel))
    for caster in model.casters:
        name = 'caster_back_link' if len(model.casters) == 1 else 'caster_back_%s_link' % (
            'left' if caster[1] > 0 else 'right')
        parts.append(_joint(name.replace('_link', '_joint'), 'fixed', link('base_link'), link(name),
                            caster))
        parts.append(_link(link(name), '<box size="0.030 0.009 0.020"/>', (0, 0, -0.001)))
    parts.append(_joint('imu_joint', 'fixed', link('base_link'), link('imu_link'),
                        model.imu_offset))
    parts.append(_link(link('imu_link')))
    parts.append(_joint('scan_joint', 'fixed', link('base_link'), link('base_scan'),
                        model.scan_offset))
    parts.append(_link(link('base_scan'), '<cylinder radius="%g" length="%g"/>' % (
        LASER_RADIUS, LASER_HEIGHT), (0, 0, -LASER_HEIGHT / 2)))
    if model.camera_offset:
        parts.append(_joint('camera_joint', 'fixed', link('base_link'), link('camera_link'),
                            model.camera_offset))
        parts.append(_link(link('camera_link'), '<box size="0.015 0.030 0.027"/>', colour='blue'))
    parts.append('</robot>\n')
    return ''.join(parts)


def main(argv):
    """Command line: turtlebot3_urdf MODEL [PREFIX] prints the URDF."""
    if len(argv) not in (2, 3):
        print('usage: turtlebot3_urdf MODEL [LINK_PREFIX]   (MODEL: burger, waffle, waffle_pi)')
        return 2
    try:
        model = get_model(argv[1])
    except UnknownModelError as err:
        print('turtlebot3_urdf: %s' % err)
        return 1
    print(turtlebot3_urdf(model, argv[2] if len(argv) == 3 else ''), end='')
    return 0
