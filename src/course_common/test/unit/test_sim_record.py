"""A simulator's record for the judge: entries read back as written, as they come; a file that exists
or a link is never written; the user at the other end of a TCP connection, as the kernel lists it."""
import os
import socket

import pytest

from course_common.sim_record import FRAME, RecordReader, RecordWriter, peer_uid


def test_entries_and_events_read_back_as_written(tmp_path):
    path = str(tmp_path / 'run.record')
    writer = RecordWriter(path)
    writer.write('scan', 2_000_000_000, 12.5, b'\x00\x01\x02')
    writer.event('command', 2_010_000_000, 12.6, linear=0.5, angular=-1.0, sender='/node (uid 1000)')
    writer.close()
    entries = RecordReader(path).read_new()
    assert [(e.name, e.sim_ns, e.wall) for e in entries] == [('scan', 2_000_000_000, 12.5), ('command', 2_010_000_000, 12.6)]
    assert entries[0].payload == b'\x00\x01\x02'
    assert entries[0].sim_time == 2.0
    assert entries[1].fields() == {'linear': 0.5, 'angular': -1.0, 'sender': '/node (uid 1000)'}


def test_the_reader_returns_each_entry_once_and_waits_for_a_half_written_one(tmp_path):
    path = str(tmp_path / 'run.record')
    reader = RecordReader(path)
    assert reader.read_new() == []                     # the simulator has not started yet
    writer = RecordWriter(path)
    writer.write('pose', 1, 1.0, b'a' * 40)
    writer.flush()
    assert [e.payload for e in reader.read_new()] == [b'a' * 40]
    assert reader.read_new() == []
    with open(path, 'ab') as stream:                   # a frame cut in its middle by a flush
        stream.write(FRAME.pack(2.0, 2, 4, 3) + b'po')
    assert reader.read_new() == []
    with open(path, 'ab') as stream:
        stream.write(b'sexyz')
    assert [(e.name, e.payload) for e in reader.read_new()] == [('pose', b'xyz')]


def test_a_file_that_exists_or_a_link_is_never_written(tmp_path):
    existing = tmp_path / 'result.json'
    existing.write_text('the grade')
    with pytest.raises(FileExistsError):
        RecordWriter(str(existing))
    link = tmp_path / 'run.record'
    link.symlink_to(tmp_path / 'elsewhere')
    with pytest.raises(OSError):
        RecordWriter(str(link))
    assert existing.read_text() == 'the grade'
    assert not (tmp_path / 'elsewhere').exists()


def test_the_record_is_the_trusted_users_alone(tmp_path):
    path = str(tmp_path / 'run.record')
    RecordWriter(path).close()
    assert os.stat(path).st_mode & 0o777 == 0o600


def test_the_user_at_the_other_end_of_a_connection_is_the_kernels_word():
    server = socket.socket()
    server.bind(('127.0.0.1', 0))
    server.listen(1)
    client = socket.create_connection(server.getsockname())
    accepted, _ = server.accept()
    try:
        assert peer_uid(client.getsockname(), client.getpeername()) == os.geteuid()
        assert peer_uid(accepted.getsockname(), accepted.getpeername()) == os.geteuid()
    finally:
        for sock in (client, accepted, server):
            sock.close()


def _table(tmp_path, lines):
    table = tmp_path / 'tcp'
    header = '  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode\n'
    table.write_text(header + ''.join(lines))
    return str(table)


def test_another_users_end_is_found_in_ipv4_and_ipv6_tables(tmp_path):
    # 127.0.0.1:11311 -> 127.0.0.1:40000, owned by uid 1000 (the kernel's byte order).
    ipv4 = _table(tmp_path, ['   0: 0100007F:2C2F 0100007F:9C40 01 00000000:00000000 00:00000000 00000000  1000        0 1\n'])
    assert peer_uid(('127.0.0.1', 40000), ('127.0.0.1', 11311), tables=(ipv4,)) == 1000
    assert peer_uid(('127.0.0.1', 40001), ('127.0.0.1', 11311), tables=(ipv4,)) is None
    # ::1 and an IPv4 address mapped into IPv6, as a dual-stack socket lists it.
    loopback6 = '00000000000000000000000001000000'
    mapped = '0000000000000000FFFF00000100007F'
    ipv6 = _table(tmp_path, ['   0: %s:2C2F %s:9C40 01 00000000:00000000 00:00000000 00000000  1001 0 2\n' % (loopback6, loopback6),
                             '   1: %s:2C30 %s:9C41 01 00000000:00000000 00:00000000 00000000  1002 0 3\n' % (mapped, mapped)])
    assert peer_uid(('::1', 40000), ('::1', 11311), tables=(ipv6,)) == 1001
    assert peer_uid(('127.0.0.1', 40001), ('127.0.0.1', 11312), tables=(ipv6,)) == 1002


def test_without_the_kernels_tables_nobody_is_named(tmp_path):
    assert peer_uid(('127.0.0.1', 1), ('127.0.0.1', 2), tables=(str(tmp_path / 'no_proc'),)) is None
