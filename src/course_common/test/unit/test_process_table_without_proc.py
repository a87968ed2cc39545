"""Where /proc is not mounted (a chroot): the processes found through a descriptor of /proc handed
down, or a sentence saying that none can be stopped, never a silent empty table."""
import os
import socket
import subprocess

import pytest

from course_common import process_table
from course_common.waiting import wait_until


@pytest.fixture
def no_proc(monkeypatch, tmp_path):
    """This process as in a chroot: its /proc an empty folder, nothing mounted there."""
    (tmp_path / 'proc').mkdir()
    monkeypatch.setattr(process_table, 'PROC', str(tmp_path / 'proc'))
    monkeypatch.delenv(process_table.PROC_FD_VARIABLE, raising=False)


def test_without_proc_the_table_is_an_error_and_stop_user_says_so(no_proc, monkeypatch, tmp_path, capsys):
    with pytest.raises(process_table.NoProcessTable, match='no process table here'):
        process_table.process_ids()
    monkeypatch.setattr(process_table, 'PROC', str(tmp_path / 'none'))
    with pytest.raises(process_table.NoProcessTable, match='no process table here'):
        process_table.process_ids()
    assert process_table.stop_user(os.getuid()) == 0
    assert ('process_table: the processes of user %d cannot be stopped: no process table here'
            % os.getuid()) in capsys.readouterr().err


def test_a_descriptor_of_proc_handed_down_finds_and_stops_the_users_processes(no_proc, monkeypatch):
    sleeper = subprocess.Popen(['sleep', '600'])
    handed_down = os.open('/proc', os.O_RDONLY | os.O_DIRECTORY)
    try:
        monkeypatch.setenv(process_table.PROC_FD_VARIABLE, str(handed_down))
        assert sleeper.pid in process_table.user_processes(os.getuid())
        # Waited for: Popen may return before the new program's command line is in place (empty
        # for a moment, on a busy machine).
        wait_until(lambda: process_table.command_line(sleeper.pid) == '%d sleep 600' % sleeper.pid, 10,
                   'the command line of sleep read through the descriptor')
        # stop_user would stop this process too (the same user): its finding is the same, but for
        # the zombie, which we reap (the process table names it until its parent does).
        assert process_table.stop_processes(lambda: [sleeper.pid] if sleeper.poll() is None else []) == 1
        assert sleeper.returncode == -9
    finally:
        sleeper.kill()
        os.close(handed_down)


def test_whose_socket_listens_on_a_port_read_through_a_descriptor_handed_down_or_an_error(no_proc, monkeypatch):
    with socket.socket() as server:
        server.bind(('127.0.0.1', 0))
        port = server.getsockname()[1]
        with pytest.raises(process_table.NoProcessTable):
            process_table.listening_sockets(port)
        assert process_table.socket_inodes(os.getpid()) == set()
        handed_down = os.open('/proc', os.O_RDONLY | os.O_DIRECTORY)
        try:
            monkeypatch.setenv(process_table.PROC_FD_VARIABLE, str(handed_down))
            assert process_table.listening_sockets(port) == set()   # bound, not listening yet
            server.listen()
            listening = process_table.listening_sockets(port)
            assert len(listening) == 1 and listening <= process_table.socket_inodes(os.getpid())
            assert not listening & process_table.socket_inodes(os.getppid())
        finally:
            os.close(handed_down)
