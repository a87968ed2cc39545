"""A student's launch file with its turtlesim node(s) left out, run on the student's side: the
grader starts the course's turtlesim itself, on the trusted side, with what the launch file gives
that node (name, namespace, remappings, private parameters), so that nothing of the student's
build (a `sitecustomize.py` in devel/, a library) runs inside it.

  python3 -m course_grader.turtlesim_launch describe PACKAGE FILE [NAME:=VALUE ...] [-- PACKAGE FILE ...]
      prints, for each launch file, one line: `turtlesim nodes: ` and, as JSON, each turtlesim node
      it declares, as roslaunch's own loader reads it (the arguments included), or why it could not;
  python3 -m course_grader.turtlesim_launch launch [--only PACKAGE/TYPE] [ROSLAUNCH OPTIONS] PACKAGE FILE
          [NAME:=VALUE ...]
      is `roslaunch` with those nodes and their private parameters left out; it starts the other
      nodes as roslaunch would, or with --only the nodes of that executable alone (a node the grader
      judges on its own, the grader standing in for the others). roscore.xml is not read: the
      grader's master has its parameters (grading_session.Master) and rosout is a core node, which
      roslaunch starts only with a master of its own. Nor is the size of the log folder checked: the
      student's side has a folder of its own at each grading.
"""
import contextlib
import json
import sys
import types

from course_grader import TURTLESIM_NODES_PREFIX as PREFIX

# roslaunch imports rosclean for the size check of the log folder alone, which this launcher skips
# (--skip-log-check: the student's side has a log folder of its own at each grading), and rosclean
# imports distutils, which on Debian loads setuptools: 0.15 - 0.2 s of the start of every run.
sys.modules.setdefault('rosclean', types.ModuleType('rosclean'))
import roslaunch  # noqa: E402 (after the line above)
import roslaunch.config  # noqa: E402
import roslaunch.parent  # noqa: E402
import roslaunch.rlutil  # noqa: E402

TURTLESIM = ('turtlesim', 'turtlesim_node')


def is_turtlesim(node):
    return (node.package, node.type) == TURTLESIM


def full_name(node):
    return node.namespace + node.name


def _private(name, node):
    return name.startswith(full_name(node) + '/')


def turtlesim_nodes(config):
    """Each turtlesim node of a loaded launch configuration: its full name, its remappings and the
    parameters in its private namespace (by their names relative to it)."""
    return [{'name': full_name(node), 'remaps': [list(pair) for pair in node.remap_args],
             'params': {name[len(full_name(node)) + 1:]: param.value
                        for name, param in sorted(config.params.items()) if _private(name, node)}}
            for node in config.nodes if is_turtlesim(node)]


def leave_out_turtlesim(config):
    """Takes the turtlesim nodes out of the configuration, with their private parameters (and the
    clearing of them): returns their full names."""
    left_out = [node for node in config.nodes if is_turtlesim(node)]
    config.nodes = [node for node in config.nodes if not is_turtlesim(node)]
    for node in left_out:
        for name in [name for name in config.params if _private(name, node)]:
            del config.params[name]
        config.clear_params = [name for name in config.clear_params
                               if not (name + '/').startswith(full_name(node) + '/')]
    return [full_name(node) for node in left_out]


def keep_only(config, package, node_type):
    """Leaves in the configuration the nodes of that executable alone: returns the full names of
    the others, taken out."""
    others = [node for node in config.nodes if (node.package, node.type) != (package, node_type)]
    config.nodes = [node for node in config.nodes if (node.package, node.type) == (package, node_type)]
    return [full_name(node) for node in others]


@contextlib.contextmanager
def without_roscore_xml():
    """roslaunch's configuration read without the roscore.xml it adds to every launch: its two
    `rosversion` commands were 0.18 s of each file's 0.19 s, and it declares no turtlesim (the
    grader's master has its parameters: grading_session.core_parameters)."""
    load_roscore = roslaunch.config.load_roscore
    roslaunch.config.load_roscore = lambda loader, config, verbose=True: None
    try:
        yield
    finally:
        roslaunch.config.load_roscore = load_roscore


class WithoutTurtlesim(roslaunch.parent.ROSLaunchParent):
    """roslaunch's parent process, its configuration read without roscore.xml and its turtlesim
    nodes left out; with `only` (package, type), the nodes of that executable alone."""
    only = None

    def _load_config(self):
        with without_roscore_xml():
            super()._load_config()
        leave_out_turtlesim(self.config)
        if self.only:
            keep_only(self.config, *self.only)


def describe(package, launch_file, args):
    """The turtlesim nodes of the file with its arguments, as roslaunch reads it (without roscore.xml)."""
    path = roslaunch.rlutil.resolve_launch_arguments([package, launch_file])[0]
    with without_roscore_xml():
        return turtlesim_nodes(roslaunch.config.load_config_default([(path, list(args))], None, verbose=False))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ['describe']:
        launches = [[]]
        for arg in argv[1:]:
            if arg == '--':
                launches.append([])
            else:
                launches[-1].append(arg)
        for launch in launches:
            try:
                line = PREFIX + json.dumps(describe(launch[0], launch[1], launch[2:]), default=str)
            except Exception as error:   # noqa: B902 (whatever roslaunch refused, in one line)
                line = 'roslaunch could not read it: %s' % str(error).replace('\n', ' ')
            print(line, flush=True)
        return 0
    if argv[:1] == ['launch']:
        argv = argv[1:]
        if argv[:1] == ['--only'] and len(argv) > 1 and argv[1].count('/') == 1:
            WithoutTurtlesim.only = tuple(argv[1].split('/'))
            argv = argv[2:]
        roslaunch.parent.ROSLaunchParent = WithoutTurtlesim
        sys.argv = ['roslaunch', '--skip-log-check'] + argv   # roslaunch's loader reads NAME:=VALUE from sys.argv
        return roslaunch.main(sys.argv)
    sys.exit(__doc__)


if __name__ == '__main__':
    sys.exit(main())
