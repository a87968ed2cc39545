"""What a turtle holds: made all or none, given back in full; the open-file budget of a spawn."""
import os
import resource
import subprocess
import sys

import pytest

from turtlesim.holdings import (FILE_RESERVE, Holdings, capacity_note, open_file_count, raise_open_file_limit,
                                spawn_refusal)


class Made:
    """Records what was made and given back, in order."""

    def __init__(self):
        self.events = []

    def step(self, label, fail=False, fail_release=False):
        def create():
            if fail:
                raise OSError(24, 'Too many open files')
            self.events.append(('made', label))
            return label

        def release(item):
            self.events.append(('released', item))
            if fail_release:
                raise RuntimeError('master unreachable')
        return label, create, release


def test_take_all_returns_the_items_in_order_and_keeps_them():
    made, holdings = Made(), Holdings()
    items = holdings.take_all([made.step('pose'), made.step('color'), made.step('cmd_vel')])
    assert items == ['pose', 'color', 'cmd_vel']
    assert holdings.labels() == ['pose', 'color', 'cmd_vel']
    assert len(holdings) == 3


def test_a_failure_half_way_gives_back_what_was_made_newest_first_and_raises():
    made, holdings = Made(), Holdings()
    with pytest.raises(OSError, match='Too many open files'):
        holdings.take_all([made.step('pose'), made.step('color'), made.step('set_pen', fail=True),
                           made.step('teleport')])
    assert made.events == [('made', 'pose'), ('made', 'color'), ('released', 'color'), ('released', 'pose')]
    assert len(holdings) == 0


def test_release_all_goes_on_past_a_failure_and_reports_it():
    made, holdings = Made(), Holdings()
    holdings.take_all([made.step('pose'), made.step('color', fail_release=True), made.step('cmd_vel')])
    failures = holdings.release_all()
    assert [label for label, _ in failures] == ['color']
    assert str(failures[0][1]) == 'master unreachable'
    assert made.events[3:] == [('released', 'cmd_vel'), ('released', 'color'), ('released', 'pose')]
    assert len(holdings) == 0
    assert holdings.release_all() == []  # a second release gives nothing back twice
    assert len(made.events) == 6


class FakeLimits:
    RLIMIT_NOFILE = resource.RLIMIT_NOFILE
    RLIM_INFINITY = resource.RLIM_INFINITY

    def __init__(self, soft, hard, refuse=False):
        self.limits, self.refuse = (soft, hard), refuse

    def getrlimit(self, _which):
        return self.limits

    def setrlimit(self, _which, limits):
        if self.refuse:
            raise ValueError('not allowed')
        self.limits = limits


def test_the_soft_open_file_limit_is_raised_to_the_hard_one():
    limits = FakeLimits(1024, 524288)
    assert raise_open_file_limit(limits) == (524288, 524288)
    assert limits.limits == (524288, 524288)
    assert raise_open_file_limit(FakeLimits(1024, 1024)) == (1024, 1024)
    assert raise_open_file_limit(FakeLimits(1024, 4096, refuse=True)) == (1024, 4096)


def test_the_limit_is_raised_in_a_real_process():
    def low_soft_limit():
        resource.setrlimit(resource.RLIMIT_NOFILE, (256, 512))
    script = ('from turtlesim.holdings import raise_open_file_limit; import resource; '
              'print(raise_open_file_limit(), resource.getrlimit(resource.RLIMIT_NOFILE))')
    out = subprocess.check_output([sys.executable, '-c', script], preexec_fn=low_soft_limit, text=True)
    assert out.strip() == '(512, 512) (512, 512)'


def test_open_file_count_counts_the_entries_of_the_fd_folder(tmp_path):
    for number in range(5):
        (tmp_path / str(number)).write_text('')
    assert open_file_count(str(tmp_path)) == 5
    assert open_file_count(str(tmp_path / 'missing')) is None
    with open(os.devnull) as _:
        assert open_file_count() >= 4  # stdin, stdout, stderr and this file


def test_a_spawn_goes_on_while_the_reserve_is_free():
    assert spawn_refusal('t', 1024 - FILE_RESERVE, 1024) is None
    assert spawn_refusal('t', 10, 1024) is None
    assert spawn_refusal('t', 10**6, resource.RLIM_INFINITY) is None


def test_a_spawn_that_would_eat_into_the_reserve_gets_a_clear_error():
    text = spawn_refusal('t7', 1024 - FILE_RESERVE + 1, 1024)
    assert text.startswith('Cannot spawn turtle [t7]: turtlesim has %d of its 1024 open files in use (ulimit -n)'
                           % (1024 - FILE_RESERVE + 1))
    assert text.endswith('kill turtles, or start it with a higher limit')
    assert spawn_refusal('', 300, 256).startswith('Cannot spawn a turtle: turtlesim has 300 of its 256')
    assert spawn_refusal('t', None, 256).startswith('Cannot spawn turtle [t]: turtlesim has all of its 256')


def test_the_capacity_note_counts_connections_after_the_reserve():
    note = capacity_note(1024, 10)
    assert note.startswith('Open-file limit 1024: a turtle holds no open file')
    assert 'room for about %d connections, e.g. %d turtles' % (1024 - 10 - FILE_RESERVE,
                                                                (1024 - 10 - FILE_RESERVE) // 2) in note
    assert 'room for about 0 connections' in capacity_note(16, 10)
