"""The grader starts fake_tb3 itself (its executable's main, prepared ahead of the run), not through
world.launch: the parameters it sets beside a run's own must be those world.launch would set, or
the run sees another simulator."""
import os
import re
import xml.etree.ElementTree as ElementTree

import rospkg
import yaml

from course_grader.labs.move_turtlebot3 import LAUNCH_DEFAULTS


def world_launch_parameters():
    """{name: value} of the parameters world.launch gives the fake_tb3 node, its args at their defaults."""
    root = ElementTree.parse(os.path.join(rospkg.RosPack().get_path('fake_tb3'), 'launch', 'world.launch')).getroot()
    defaults = {arg.get('name'): arg.get('default') for arg in root.iter('arg')}
    node = root.find('node')
    parameters = {}
    for param in node.findall('param'):
        text = re.sub(r'\$\(arg (\w+)\)', lambda match: defaults[match.group(1)], param.get('value'))
        parameters[param.get('name')] = text if param.get('type') == 'str' else yaml.safe_load(text)
    for rosparam in node.findall('rosparam'):
        parameters[rosparam.get('param')] = yaml.safe_load(rosparam.text)
    return parameters


def test_the_grader_sets_what_world_launch_sets_beside_a_runs_settings():
    launched = world_launch_parameters()
    assert {name: launched[name] for name in LAUNCH_DEFAULTS} == LAUNCH_DEFAULTS
