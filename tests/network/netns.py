"""Two hosts on one machine: two network namespaces joined by a veth pair (iproute2).

Both ends of the pair are created inside the namespaces and the only addresses are 10.200.0.1/24 and
10.200.0.2/24 there: nothing is added to the machine's own network, and nothing can leave it.
Needs root (CAP_NET_ADMIN); the Docker image's non-root user cannot run it.
"""
import os
import re
import subprocess

from rosnet import project_environment

HOST_A_ADDRESS = '10.200.0.1'
HOST_B_ADDRESS = '10.200.0.2'
PREFIX = 'rosres'
IP_TIMEOUT = 10


def _run(*argv):
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            universal_newlines=True, timeout=IP_TIMEOUT)
    if result.returncode != 0:
        raise AssertionError('%s failed: %s' % (' '.join(argv), result.stdout.strip()))
    return result.stdout


def require_root():
    if os.geteuid() != 0:
        raise AssertionError(
            'the two-host tests create network namespaces and need root (CAP_NET_ADMIN); '
            'run them as root, on a CI host rather than in the Docker image')


def remove_stale_namespaces():
    """Namespaces of earlier runs whose pytest died before cleaning up (named after its PID)."""
    for name in re.findall(r'^(%s_[ab]_(\d+))' % PREFIX, _run('ip', 'netns', 'list'), re.MULTILINE):
        namespace, pid = name
        if not os.path.exists('/proc/%s' % pid):
            subprocess.run(['ip', 'netns', 'delete', namespace], timeout=IP_TIMEOUT)


class TwoHosts:
    """Host A and host B; `cut()` and `restore()` the link between them."""

    def __init__(self):
        tag = os.getpid()
        self.a, self.b = '%s_a_%d' % (PREFIX, tag), '%s_b_%d' % (PREFIX, tag)
        self.link_a, self.link_b = 'vra%d' % tag, 'vrb%d' % tag  # interface names: 15 characters at most

    def create(self):
        require_root()
        remove_stale_namespaces()
        _run('ip', 'netns', 'add', self.a)
        _run('ip', 'netns', 'add', self.b)
        _run('ip', 'link', 'add', self.link_a, 'netns', self.a, 'type', 'veth',
             'peer', 'name', self.link_b, 'netns', self.b)
        for namespace, link, address in ((self.a, self.link_a, HOST_A_ADDRESS),
                                         (self.b, self.link_b, HOST_B_ADDRESS)):
            _run('ip', '-n', namespace, 'addr', 'add', address + '/24', 'dev', link)
            _run('ip', '-n', namespace, 'link', 'set', 'lo', 'up')
            _run('ip', '-n', namespace, 'link', 'set', link, 'up')
        return self

    def delete(self):
        """Remove both namespaces (and with them the veth pair); safe to call twice."""
        for namespace in (self.a, self.b):
            subprocess.run(['ip', 'netns', 'delete', namespace], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, timeout=IP_TIMEOUT)

    def _ends(self):
        return ((self.a, self.link_a), (self.b, self.link_b))

    def cut(self, how):
        """'down': both ends administratively down; 'loss': every packet dropped both ways while the
        link stays up (the blackhole qdisc: what `netem loss 100%` does, without needing the netem
        module, which many kernels lack)."""
        for namespace, link in self._ends():
            if how == 'down':
                _run('ip', '-n', namespace, 'link', 'set', link, 'down')
            else:
                _run('ip', 'netns', 'exec', namespace, 'tc', 'qdisc', 'add', 'dev', link, 'root', 'blackhole')

    def restore(self, how):
        for namespace, link in self._ends():
            if how == 'down':
                _run('ip', '-n', namespace, 'link', 'set', link, 'up')
            else:
                _run('ip', 'netns', 'exec', namespace, 'tc', 'qdisc', 'del', 'dev', link, 'root')

    def environment(self, host):
        """What the README tells a user on each machine to export before `source tools/env.sh`."""
        return project_environment(ROS_MASTER_URI='http://%s:11311' % HOST_A_ADDRESS,
                                   ROS_IP=HOST_A_ADDRESS if host == self.a else HOST_B_ADDRESS)
