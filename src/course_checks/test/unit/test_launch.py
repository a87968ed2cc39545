"""course_checks.launch.Launch: the output of a command is read to its end whatever happens to its log."""
from course_checks.launch import Launch

LINES = 100000   # far more than a pipe holds (64 KiB): the command ends only if we keep reading


def test_a_full_disk_ends_the_log_but_not_the_reading():
    # /dev/full refuses every write (ENOSPC), as a log folder on a disk a submission filled.
    launch = Launch(['seq', str(LINES)], log_path='/dev/full')
    assert launch.process.wait(timeout=30) == 0
    launch.stop()
    assert launch.lines[-1] == str(LINES)


def test_the_log_keeps_the_output(tmp_path):
    log = tmp_path / 'seq.log'
    launch = Launch(['seq', '3'], log_path=str(log))
    assert launch.process.wait(timeout=30) == 0
    launch.stop()
    assert log.read_text() == '1\n2\n3\n'
    assert launch.lines == ['1', '2', '3']
