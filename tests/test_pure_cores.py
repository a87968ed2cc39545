"""The simulators' pure cores import without ROS: every module of turtlesim and fake_tb3 except
their ROS layers imports in a Python where rospy (and every other ROS client library or message
package) cannot be imported. A new module counts as core unless it is listed as a ROS layer."""
import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGES = {
    'turtlesim': ('src/turtlesim/src/turtlesim',
                  {'node', 'window', 'teleop_key', 'draw_square', 'mimic', 'scene_topic',
                   'ticks', 'canvas_outputs'}),
    'fake_tb3': ('src/fake_tb3/src/fake_tb3', {'node', 'turtlebot3_drive_node'}),
    'course_web': ('src/course_web/src/course_web', {'ros_view', 'follow_master', 'replay'}),
}
# Run in a fresh interpreter: a finder first on sys.meta_path refuses every ROS module.
IMPORT_WITHOUT_ROS = r'''
import importlib, json, sys

ROS = ('rospy', 'rosgraph', 'rospkg', 'roslib', 'genpy', 'tf2_ros', 'rosnode', 'rostopic')


class RefuseRos:
    def find_spec(self, name, path=None, target=None):
        top, last = name.split('.')[0], name.split('.')[-1]
        if top in ROS or top.endswith(('_msgs', '_srvs')) or last in ('msg', 'srv'):
            raise ImportError('%s is ROS, not available here' % name)
        return None


sys.meta_path.insert(0, RefuseRos())
results = {}
for module in sys.argv[1:]:
    try:
        importlib.import_module(module)
        results[module] = None
    except Exception as error:  # what went wrong is the test's message
        results[module] = '%s: %s' % (type(error).__name__, error)
print(json.dumps(results))
'''


def modules(package):
    folder, ros_layer = PACKAGES[package]
    names = sorted(name[:-3] for name in os.listdir(os.path.join(ROOT, folder))
                   if name.endswith('.py') and name != '__init__.py')
    return (['%s.%s' % (package, name) for name in names if name not in ros_layer],
            ['%s.%s' % (package, name) for name in sorted(ros_layer)])


def import_without_ros(names):
    run = subprocess.run([sys.executable, '-c', IMPORT_WITHOUT_ROS] + names,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


@pytest.mark.parametrize('package', sorted(PACKAGES))
def test_the_core_imports_without_ros(package):
    core, ros_layer = modules(package)
    results = import_without_ros(core + ros_layer)
    failed = {name: error for name, error in results.items() if name in core and error}
    assert not failed, 'core modules that need ROS: %s' % failed
    # The ROS layers do need rospy: proof that ROS really was out of reach.
    for name in ros_layer:
        assert results[name] and 'is ROS, not available here' in results[name], (name, results)
    assert len(core) >= 3
