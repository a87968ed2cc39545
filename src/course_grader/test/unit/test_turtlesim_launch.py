"""A student's launch file as the grader runs it: the turtlesim nodes it declares (name, namespace,
remappings, private parameters, as roslaunch's loader reads them) are left out of what the student's
side launches, and what reaches the trusted turtlesim is checked."""
import sys

import pytest
import roslaunch
import roslaunch.config
import roslaunch.core
import roslaunch.xmlloader

from course_grader import turtlesim_launch
from course_grader.labs.turtlesim_runs import _node
from course_grader.grading_session import core_parameters
from course_grader.turtlesim_launch import WithoutTurtlesim, describe, keep_only, leave_out_turtlesim, turtlesim_nodes

LAUNCH = '''<launch>
  <arg name="colour" default="10"/>
  <param name="/shared" value="1"/>
  <group ns="lab">
    <node pkg="turtlesim" type="turtlesim_node" name="sim" clear_params="true">
      <param name="background_r" value="$(arg colour)"/>
      <remap from="turtle1/cmd_vel" to="robot/cmd_vel"/>
    </node>
  </group>
  <node pkg="ros_exercises" type="circle" name="circle">
    <param name="speed" value="2"/>
  </node>
  <node pkg="ros_exercises" type="turtlesim_node" name="turtlesim"/>
</launch>'''


def loaded(folder, argv=()):
    path = folder / 'exercise.launch'
    path.write_text(LAUNCH)
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(str(path), config, argv=list(argv), verbose=False)
    return config


def test_the_turtlesim_node_is_described_with_its_name_remappings_and_private_parameters(tmp_path):
    assert turtlesim_nodes(loaded(tmp_path, ['colour:=200'])) == [
        {'name': '/lab/sim', 'remaps': [['turtle1/cmd_vel', 'robot/cmd_vel']], 'params': {'background_r': 200}}]


def test_only_the_turtlesim_node_and_its_parameters_are_left_out(tmp_path):
    config = loaded(tmp_path)
    assert leave_out_turtlesim(config) == ['/lab/sim']
    # A node of the student's package named like turtlesim is the student's: it stays (and is judged).
    assert sorted(node.namespace + node.name for node in config.nodes) == ['/circle', '/turtlesim']
    assert sorted(config.params) == ['/circle/speed', '/shared']
    assert config.clear_params == []


def test_one_executable_s_node_alone(tmp_path):
    """--only PACKAGE/TYPE: exercise 1's subscriber run without the publisher its launch file
    includes; the package's node named like turtlesim is another executable's, left out too."""
    config = loaded(tmp_path)
    leave_out_turtlesim(config)
    assert keep_only(config, 'ros_exercises', 'circle') == ['/turtlesim']
    assert [node.namespace + node.name for node in config.nodes] == ['/circle']
    assert keep_only(loaded(tmp_path), 'ros_exercises', 'subscriber') == ['/lab/sim', '/circle', '/turtlesim']


def test_what_reaches_the_trusted_turtlesim_is_checked():
    declared = {'name': '/lab/sim', 'remaps': [['turtle1/pose', 'robot/pose'], ['__log', '/grader/x'],
                                                ['__master', 'http://elsewhere:1'], ['a', 'b:=c']],
                'params': {'background_g': 5, 'canvas_png': '/grader/result.json', 'real_time_factor': 1000,
                           'lock_step': False, '../../use_sim_time': False, '/abs': 1}}
    assert _node(declared) == {'name': '/lab/sim', 'remaps': [('turtle1/pose', 'robot/pose')],
                               'params': {'background_g': 5}}
    assert _node({'name': '__master'}) is None
    assert _node(['not', 'a', 'node']) is None


PACKAGE_XML = ('<package format="2"><name>lab</name><version>0.0.0</version><description>d</description>'
               '<maintainer email="s@example.org">s</maintainer><license>BSD</license></package>')


def test_describe_reads_a_package_s_launch_file_as_roslaunch_does(tmp_path, monkeypatch):
    """describe(PACKAGE, FILE, ARGS): the package found on ROS_PACKAGE_PATH, its arguments given
    or refused in roslaunch's own words, roscore's configuration left out (no node of it appears)."""
    package = tmp_path / 'lab'
    (package / 'launch').mkdir(parents=True)
    (package / 'package.xml').write_text(PACKAGE_XML)
    (package / 'launch' / 'exercise.launch').write_text(LAUNCH.replace('default="10"', ''))
    monkeypatch.setenv('ROS_PACKAGE_PATH', str(tmp_path))
    assert describe('lab', 'exercise.launch', ['colour:=7']) == [
        {'name': '/lab/sim', 'remaps': [['turtle1/cmd_vel', 'robot/cmd_vel']], 'params': {'background_r': 7}}]
    with pytest.raises(roslaunch.core.RLException, match="requires the 'colour' arg to be set"):
        describe('lab', 'exercise.launch', [])


def test_the_student_s_roslaunch_reads_no_roscore_xml_and_the_master_has_its_parameters(tmp_path):
    """What the student's side launches: the file's own nodes and parameters, without turtlesim and
    without roscore.xml's; the grader's master sets those as roscore.xml would."""
    path = tmp_path / 'exercise.launch'
    path.write_text(LAUNCH)
    parent = WithoutTurtlesim('run', [str(path)], is_core=False)
    parent._load_config()
    assert sorted(parent.config.params) == ['/circle/speed', '/shared']
    assert sorted(node.namespace + node.name for node in parent.config.nodes) == ['/circle', '/turtlesim']
    assert parent.config.nodes_core == []
    roscore = roslaunch.config.ROSLaunchConfig()
    roslaunch.config.load_roscore(roslaunch.xmlloader.XmlLoader(), roscore, verbose=False)
    assert core_parameters() == {name: param.value for name, param in roscore.params.items()}


def test_launch_with_only_starts_that_executable_s_nodes_alone(tmp_path, monkeypatch):
    path = tmp_path / 'exercise.launch'
    path.write_text(LAUNCH)
    handed = []
    monkeypatch.setattr(roslaunch, 'main', lambda argv: handed.append(list(argv)) or 0)
    monkeypatch.setattr(turtlesim_launch.WithoutTurtlesim, 'only', None)
    # main() replaces roslaunch's parent class and sys.argv, as in its own process: restored after.
    monkeypatch.setattr(roslaunch.parent, 'ROSLaunchParent', roslaunch.parent.ROSLaunchParent)
    monkeypatch.setattr(sys, 'argv', list(sys.argv))
    assert turtlesim_launch.main(['launch', '--only', 'ros_exercises/circle', str(path), 'colour:=3']) == 0
    # roslaunch's loader reads NAME:=VALUE there; the log folder's size is not checked (the launcher's rosclean)
    assert handed == [['roslaunch', '--skip-log-check', str(path), 'colour:=3']]
    parent = roslaunch.parent.ROSLaunchParent('run', [str(path)], is_core=False)
    parent._load_config()
    assert [node.namespace + node.name for node in parent.config.nodes] == ['/circle']
