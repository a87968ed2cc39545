"""course_checks.launch.Launch.timed_lines: each line with the moment it was read, so that a check
can tell when a node printed what it printed."""
import time

from course_checks.launch import Launch
from course_common.waiting import wait_until


def test_each_line_comes_with_the_time_it_was_read(tmp_path):
    go = tmp_path / 'go'
    launch = Launch(['sh', '-c', 'echo first; while [ ! -e %s ]; do sleep 0.01; done; echo second' % go])
    wait_until(lambda: launch.lines == ['first'], 30, 'the first line')
    between = time.monotonic()   # the second line is printed only after this
    go.touch()
    assert launch.process.wait(timeout=30) == 0
    launch.stop()
    (first_read, first), (second_read, second) = launch.timed_lines()
    assert (first, second) == ('first', 'second')
    assert first_read <= between <= second_read <= time.monotonic()
    assert launch.lines == ['first', 'second']
