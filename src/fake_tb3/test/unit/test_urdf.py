"""The URDF in simple shapes: the frames and joints of turtlebot3_description, per model."""
import xml.etree.ElementTree as ET

import pytest

from fake_tb3.models import get_model
from fake_tb3.urdf import main, turtlebot3_urdf


def joints(model_name, prefix=''):
    robot = ET.fromstring(turtlebot3_urdf(get_model(model_name), prefix))
    return {joint.get('name'): (joint.get('type'), joint.find('parent').get('link'),
                                joint.find('child').get('link'),
                                tuple(float(v) for v in joint.find('origin').get('xyz').split()))
            for joint in robot.iter('joint')}


def test_burger_frames():
    burger = joints('burger')
    assert burger['base_joint'] == ('fixed', 'base_footprint', 'base_link', (0, 0, 0.010))
    assert burger['wheel_left_joint'] == ('continuous', 'base_link', 'wheel_left_link',
                                          (0, 0.08, 0.023))
    assert burger['wheel_right_joint'][3] == (0, -0.08, 0.023)
    assert burger['scan_joint'] == ('fixed', 'base_link', 'base_scan', (-0.032, 0, 0.172))
    assert burger['imu_joint'][3] == (-0.032, 0, 0.068)
    assert burger['caster_back_joint'][3] == (-0.081, 0, -0.004)
    assert 'camera_joint' not in burger


def test_waffles_frames_and_prefix():
    waffle = joints('waffle', 'tb3_1/')
    assert waffle['scan_joint'] == ('fixed', 'tb3_1/base_link', 'tb3_1/base_scan',
                                    (-0.064, 0, 0.122))
    assert waffle['wheel_left_joint'][3] == (0, 0.144, 0.023)
    assert waffle['caster_back_left_joint'][3] == (-0.177, 0.064, -0.004)
    assert waffle['camera_joint'][3] == (0.064, -0.065, 0.094)
    assert joints('waffle_pi')['camera_joint'][3] == (0.073, -0.011, 0.084)


def test_command_line(capsys):
    assert main(['turtlebot3_urdf', 'burger']) == 0
    assert '<robot name="turtlebot3_burger">' in capsys.readouterr().out
    assert main(['turtlebot3_urdf', 'tank']) == 1
    assert "unknown TurtleBot3 model 'tank'" in capsys.readouterr().out
    assert main(['turtlebot3_urdf']) == 2
    assert 'usage: turtlebot3_urdf MODEL' in capsys.readouterr().out


@pytest.mark.parametrize('model', ['burger', 'waffle', 'waffle_pi'])
def test_every_link_but_the_footprint_and_imu_has_a_shape(model):
    robot = ET.fromstring(turtlebot3_urdf(get_model(model)))
    bare = {link.get('name') for link in robot.iter('link') if link.find('visual') is None}
    assert bare == {'base_footprint', 'imu_link'}
