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


# Judged in time: blocks as (time read, values), scans as (time sent, LaserScan), in seconds.
PERIOD = 0.02      # a scan every 0.02 wall s (5 Hz at 10x)
WINDOW = 0.1


def sent(count):
    """`count` scans, each unlike the one before (a turning robot), one every PERIOD from 0."""
    return [(i * PERIOD, scan(1.0 + i / 10)) for i in range(count)]


def block(read, message):
    return (read, values(message))


def test_each_scan_printed_as_it_comes_is_shown_in_order():
    scans = sent(5)
    blocks = [block(t + 0.002, message) for t, message in scans[1:]]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == [1, 2, 3, 4]
    verdict = laser.printed_in_time(blocks, scans, BEAMS, 4, WINDOW)
    assert verdict.passed
    assert verdict.reason == ('4 scans printed (4 needed), each a later scan than the one before, printed 2.0 to '
                              '2.0 ms after it was sent')


def test_a_node_that_skips_scans_or_lags_within_the_window_passes():
    scans = sent(10)
    blocks = [block(scans[2][0] + 0.09, scans[2][1]), block(scans[7][0] + 0.001, scans[7][1])]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == [2, 7]
    assert laser.printed_in_time(blocks, scans, BEAMS, 2, WINDOW).passed


def test_a_stored_block_printed_again_and_again_fails_at_its_second_print():
    scans = sent(60)
    stored = scans[3][1]
    blocks = [block(scans[3][0] + 0.01 + k * 0.2, stored) for k in range(8)]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == [3]
    verdict = laser.printed_in_time(blocks, scans, BEAMS, 8, WINDOW)
    assert not verdict.passed
    assert verdict.reason == (
        "8 scans printed; block 2, printed 0.270 s after the first scan, shows no scan of the 0.100 s before it "
        "later than block 1's (it printed %s; that scan, sent 0.210 s before it, was printed already by block 1)"
        % ', '.join(values(stored)))


def test_a_block_of_no_scan_sent_fails_with_what_it_printed():
    scans = sent(5)
    blocks = [block(0.05, scans[2][1]), (0.07, ['1.0', '2.0', '3.0', '4.0', '5.0'])]
    verdict = laser.printed_in_time(blocks, scans, BEAMS, 2, WINDOW)
    assert not verdict.passed
    assert verdict.reason.endswith('block 2, printed 0.070 s after the first scan, shows no scan of the 0.100 s '
                                   "before it later than block 1's (it printed 1.0, 2.0, 3.0, 4.0, 5.0; no scan "
                                   'sent had those ranges)')


def test_a_scan_printed_later_than_the_window_fails_with_its_age():
    scans = sent(40)
    blocks = [block(scans[5][0] + 0.5, scans[5][1])]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == []
    assert laser.printed_in_time(blocks, scans, BEAMS, 1, WINDOW).reason.endswith(
        'the scan with those ranges was sent 0.500 s before it)')


def test_a_block_read_after_a_machine_pause_is_the_scan_of_its_moment_within_the_scans_of_the_window():
    # The machine paused 1.5 s between scan 9 and its block, the simulator with it: no scan sent
    # meanwhile. The block is older than the window in wall seconds, not in the scans sent since.
    scans = sent(10) + [(9 * PERIOD + 1.5 + i * PERIOD, scan(2.0 + i / 10)) for i in range(1, 4)]
    blocks = [block(scans[9][0] + 1.5 + PERIOD + 0.001, scans[9][1]), block(scans[11][0] + 0.002, scans[11][1])]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == []
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW, window_scans=5) == [9, 11]
    assert laser.printed_in_time(blocks, scans, BEAMS, 2, WINDOW, 5).passed


def test_a_block_behind_by_more_scans_and_seconds_than_the_window_fails():
    # A node that lags alone (the simulator sending on): 8 scans behind, 0.16 s.
    scans = sent(20)
    blocks = [block(scans[12][0] + 0.165, scans[12][1])]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW, window_scans=5) == []
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW, window_scans=9) == [12]
    assert laser.printed_in_time(blocks, scans, BEAMS, 1, WINDOW, 5).reason.endswith(
        'the scan with those ranges was sent 0.165 s before it)')


def test_a_scan_printed_before_it_was_sent_is_no_scan_of_its_moment():
    scans = sent(5)
    blocks = [block(scans[4][0] - 0.01, scans[4][1])]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW, window_scans=5) == []
    assert laser.printed_in_time(blocks, scans, BEAMS, 1, WINDOW).reason.endswith(
        'the scan with those ranges was sent 0.010 s after it)')


def test_scans_printed_out_of_order_fail_at_the_older_one():
    scans = sent(5)
    blocks = [block(0.065, scans[3][1]), block(0.07, scans[2][1])]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == [3]
    assert laser.printed_in_time(blocks, scans, BEAMS, 2, WINDOW).reason.endswith(
        'the scan with those ranges, sent 0.030 s before it, came before the one block 1 printed)')


def test_alike_scans_in_a_row_are_each_printed_once():
    # A robot standing still without noise: every scan alike, each block takes the next one.
    scans = [(i * PERIOD, scan(1.0)) for i in range(4)]
    blocks = [block(t + 0.001, message) for t, message in scans]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == [0, 1, 2, 3]


def test_values_rounded_to_3_decimals_show_the_scan_and_too_few_blocks_fail():
    scans = sent(3)
    rounded = ['%.3f' % value for value in laser.beam_ranges(scans[1][1], BEAMS)]
    blocks = [(scans[1][0] + 0.001, rounded)]
    assert laser.shown_scans(blocks, scans, BEAMS, WINDOW) == [1]
    verdict = laser.printed_in_time(blocks, scans, BEAMS, 2, WINDOW)
    assert not verdict.passed
    assert verdict.reason.startswith('1 scans printed (2 needed)')


def test_a_block_is_timed_by_its_last_line_and_a_cut_block_is_passed_over():
    lines = printed(['1', '2', '3', '4', '5'], ['6', '7', '8', '9', '10'])   # roslaunch's line, 2 x 11, fake_tb3's
    timed = [(float(i), line) for i, line in enumerate(lines)]
    assert laser.timed_blocks(timed) == [(11.0, ['1', '2', '3', '4', '5']), (22.0, ['6', '7', '8', '9', '10'])]
    assert laser.timed_blocks(timed[:20]) == [(11.0, ['1', '2', '3', '4', '5'])]


def test_a_block_read_before_its_last_value_is_not_yet_a_block():
    """The node prints each label and value on lines of their own: the grader may read the output
    between the fifth label and its value (CI: an IndexError cost laser_data its 3 points)."""
    lines = printed(['1', '2', '3', '4', '5'], ['6', '7', '8', '9', '10'])   # the second block: lines 12 - 22
    timed = [(float(i), line) for i, line in enumerate(lines)]
    for cut in range(12, 23):
        assert laser.timed_blocks(timed[:cut]) == [(11.0, ['1', '2', '3', '4', '5'])], cut
        assert laser.printed_blocks(lines[:cut]) == [['1', '2', '3', '4', '5']], cut
    assert laser.printed_blocks(lines[:23]) == [['1', '2', '3', '4', '5'], ['6', '7', '8', '9', '10']]


def stamped(count):
    """sent(count), each scan stamped with its simulated time (a scan every 0.2 simulated s)."""
    scans = sent(count)
    for i, (_, message) in enumerate(scans):
        message.header.stamp.secs, message.header.stamp.nsecs = divmod(i * 200000000, 1000000000)
    return scans


def test_judged_from_the_turn_on_only_the_scans_after_it_and_blocks_read_since_the_first_of_them():
    scans = stamped(10)                          # stamps 0.0, 0.2, ... 1.8 simulated s
    blocks = [block(t + 0.001, message) for t, message in scans]
    judged_blocks, judged_scans = laser.since(0.9, blocks, scans)
    assert [message.header.stamp.to_sec() for _, message in judged_scans] == [1.0, 1.2, 1.4, 1.6, 1.8]
    assert judged_blocks == blocks[5:]
    assert laser.printed_in_time(judged_blocks, judged_scans, BEAMS, 5, WINDOW).passed


def test_a_scan_stamped_at_the_turn_itself_is_of_before_it():
    scans = stamped(3)
    assert [message.header.stamp.to_sec() for _, message in laser.since(0.2, [], scans)[1]] == [0.4]


def test_blocks_of_the_scans_before_the_turn_do_not_count():
    # A stored printout of the robot standing still (the scans before the turn, the same in every
    # grading with the seeded noise), printed as if each came: nothing of it is judged.
    scans = stamped(10)
    stored = [block(t + 0.001, message) for t, message in scans[:5]]
    later = [(scans[5][0] + 0.001 + k * PERIOD, values(scans[k][1])) for k in range(5)]
    judged_blocks, judged_scans = laser.since(0.9, stored + later, scans)
    assert judged_blocks == later
    verdict = laser.printed_in_time(judged_blocks, judged_scans, BEAMS, 5, WINDOW)
    assert not verdict.passed and 'no scan of the 0.100 s before it' in verdict.reason


def test_no_scan_after_the_turn_leaves_nothing_to_judge():
    scans = stamped(4)
    assert laser.since(5.0, [block(t, message) for t, message in scans], scans) == ([], [])
