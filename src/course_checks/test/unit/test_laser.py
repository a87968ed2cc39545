"""The laser lines: the slide's blocks found in any output, and judged against the scans published."""
import math

from sensor_msgs.msg import LaserScan

from course_checks import laser

BEAMS = [0, 90, 180, 270, 359]


def printed(*blocks):
    """Output lines as laser_data.py prints them, between lines of roslaunch's."""
    lines = ['started roslaunch server']
    for values in blocks:
        lines.append('=' * 7)   # the slide's separator is cut short
        for label, value in zip(laser.LABELS, values):
            lines += [label, value]
    return laser.normalized(lines + ['[fake_tb3-1] process has finished cleanly'])


def scan(first):
    ranges = [first + i / 1000 for i in range(360)]
    return LaserScan(ranges=ranges)


def values(message):
    return [str(message.ranges[i]) for i in BEAMS]


def test_blocks_of_published_scans_pass():
    scans = [scan(1.0), scan(1.5), scan(2.0), scan(2.5)]
    blocks = laser.printed_blocks(printed(*map(values, scans)))
    verdict = laser.printed_scans(blocks, scans, BEAMS, 4)
    assert verdict.passed and verdict.reason == '4 scans printed, 2 of 2 checked match a published scan'


def test_a_made_up_block_fails_and_is_shown():
    scans = [scan(1.0), scan(1.5), scan(2.0)]
    blocks = laser.printed_blocks(printed(values(scans[0]), ['1.0', '2.0', '3.0', '4.0', '5.0'], values(scans[2])))
    verdict = laser.printed_scans(blocks, scans, BEAMS, 3)
    assert not verdict.passed
    assert verdict.reason == '3 scans printed, 0 of 1 checked match a published scan (one printed 1.0, 2.0, 3.0, 4.0, 5.0)'


def test_too_few_blocks_fail_and_rounding_to_3_decimals_passes():
    scans = [scan(1.0)]
    rounded = ['%.3f' % value for value in scans[0].ranges[:1]] + values(scans[0])[1:]
    assert laser.printed_scans(laser.printed_blocks(printed(rounded)), scans, BEAMS, 1).passed
    assert not laser.printed_scans(laser.printed_blocks(printed(rounded)), scans, BEAMS, 2).passed


def test_a_missing_beam_is_nan_on_both_sides():
    short = LaserScan(ranges=[math.nan] * 100)
    assert laser.unmatched_blocks([['nan', 'nan', 'x', 'x', 'x']], [short], BEAMS) == [['nan', 'nan', 'x', 'x', 'x']]
    assert laser.unmatched_blocks([['nan'] * 5], [short], BEAMS) == []
