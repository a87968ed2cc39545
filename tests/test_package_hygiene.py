"""Every package passes catkin_lint -W3 and the README's commands exist as the README prints them."""
import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_catkin_lint_is_clean_at_warning_level_3():
    result = subprocess.run(['catkin_lint', '-W3', '--strict', os.path.join(ROOT, 'src')],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    assert result.returncode == 0, result.stdout


def test_readme_commands_are_executable_scripts_here():
    readme = open(os.path.join(ROOT, 'README.md')).read()
    commands = set(re.findall(r'^\s*(\./[\w.-]+)', readme, re.MULTILINE))
    assert {'./demo.sh', './test.sh'} <= commands
    for command in commands:
        assert os.access(os.path.join(ROOT, command), os.X_OK), command


def test_ci_runs_exactly_the_readme_test_command():
    ci = open(os.path.join(ROOT, '.ci', 'run')).read()
    assert re.search(r'^\./test\.sh$', ci, re.MULTILINE)


def python_sources():
    """Every Python file of the project: *.py and the executables whose first line runs python3."""
    for folder in ('src', 'tests', 'bench', 'tools'):
        for parent, _, names in os.walk(os.path.join(ROOT, folder)):
            for name in names:
                path = os.path.join(parent, name)
                if name.endswith('.py'):
                    yield path
                elif os.access(path, os.X_OK) and os.path.isfile(path):
                    with open(path, 'rb') as source:
                        if source.readline().startswith(b'#!/usr/bin/env python3'):
                            yield path


def test_python_has_no_unused_imports_or_undefined_names():
    sources = sorted(python_sources())
    assert len(sources) > 50
    result = subprocess.run(['/usr/bin/python3', '-m', 'pyflakes'] + sources,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    assert result.returncode == 0, result.stdout


def test_test_command_refuses_an_unknown_package_before_doing_anything():
    result = subprocess.run([os.path.join(ROOT, 'test.sh'), 'no_such_package'],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    assert result.returncode == 2
    assert result.stdout.startswith('test: no package named no_such_package here; the packages are:')
    assert 'turtlesim' in result.stdout.split()


def test_demo_help_lists_the_labs():
    result = subprocess.run([os.path.join(ROOT, 'demo.sh'), '--help'], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, universal_newlines=True)
    assert result.returncode == 0, result.stdout
    assert 'usage: ./demo.sh [-h] [--output DIR] [LAB ...]' in result.stdout
    assert 'square, turtle, teleop, report, laser, avoid, rviz' in ' '.join(result.stdout.split())
