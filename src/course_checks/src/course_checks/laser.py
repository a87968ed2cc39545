"""The laser lines laser_data.py prints (the slide's five beams under a line of '='), and whether
they are ranges of scans the simulator published: any of them (printed_scans), or, with the time
each line was read and each scan sent, the scan of the moment each block was printed, in order
(printed_in_time)."""
import bisect
import math

from course_checks.verdict import Verdict

LABELS = ['s1 [0]', 's2 [90]', 's3 [180]', 's4 [270]', 's5 [359]']
SEPARATOR = '=' * 10


def normalized(lines):
    """Output lines stripped, with the separator line of any length (the slide's is cut short) as
    SEPARATOR."""
    stripped = [line.strip() for line in lines]
    return [SEPARATOR if len(s) >= 3 and set(s) == {'='} else s for s in stripped]


def _block_starts(lines):
    """Where each complete block printed with the slide's labels begins (its separator). Complete:
    its fifth value printed too (the output may have been read between the label and its value)."""
    return [start for start, line in enumerate(lines)
            if line == SEPARATOR and len(lines) > start + 10 and lines[start + 1:start + 11][0::2] == LABELS]


def printed_blocks(lines):
    """The complete blocks printed with the slide's labels: lists of the 5 values (text). Anything
    else in the output (roslaunch, fake_tb3) is passed over."""
    return [lines[start + 2:start + 11:2] for start in _block_starts(lines)]


def timed_blocks(timed_lines):
    """(time the block's last line was read, its 5 values) of each complete block in output lines
    given as (time.monotonic() read, line)."""
    lines = normalized([line for _, line in timed_lines])
    return [(timed_lines[start + 10][0], lines[start + 2:start + 11:2]) for start in _block_starts(lines)]


def _as_number(text):
    try:
        return float(text)
    except ValueError:
        return None


def same_range(printed, sent):
    """A printed value (text) is the range sent (to the 3 decimals a student may round to)."""
    printed = _as_number(printed)
    if printed is None:
        return False
    if math.isnan(sent) or math.isnan(printed):
        return math.isnan(sent) and math.isnan(printed)
    return printed == sent or abs(printed - sent) <= 1e-3


def beam_ranges(scan, beams):
    """The scan's ranges at `beams`, nan for a beam it does not have."""
    return [scan.ranges[i] if i < len(scan.ranges) else math.nan for i in beams]


def shows(block, ranges):
    """A printed block (text) is these ranges."""
    return all(same_range(p, s) for p, s in zip(block, ranges))


def unmatched_blocks(blocks, scans, beams):
    """The printed blocks that are no published scan's ranges at those beams."""
    published = [beam_ranges(scan, beams) for scan in scans]
    return [block for block in blocks if not any(shows(block, ranges) for ranges in published)]


def printed_scans(blocks, scans, beams, needed):
    """At least `needed` blocks were printed, and each is the ranges at `beams` of a scan that was
    published. The first and the newest block are not checked: their scan may have come before
    the checker listened, or not reached it yet."""
    checked = blocks[1:-1] or blocks
    unmatched = unmatched_blocks(checked, scans, beams)
    seen = '%d scans printed, %d of %d checked match a published scan' % (
        len(blocks), len(checked) - len(unmatched), len(checked))
    if unmatched:
        seen += ' (one printed %s)' % ', '.join(unmatched[0])
    return Verdict(len(blocks) >= needed and not unmatched, seen)


def since(turned, blocks, sent):
    """(blocks, scans) to judge from the moment `turned` (simulated s) on: the (time sent, LaserScan)
    scans stamped after it, and the (time read, values) blocks read once the first of those was
    sent (a block read before can show only a scan of before)."""
    sent = [(at, scan) for at, scan in sent if scan.header.stamp.to_sec() > turned]
    first = sent[0][0] if sent else math.inf
    return [(read, block) for read, block in blocks if read >= first], sent


def shown_scans(blocks, sent, beams, window, window_scans=0):
    """Which scan each printed block shows, in order. For (time.monotonic() read, values) blocks and
    (time.monotonic() sent, LaserScan) scans, in the order sent: the index of the first scan after
    the previous block's whose ranges the block printed, sent before the block was read, at most
    `window` s before or among the last `window_scans` scans sent before (the window at the
    simulator's own pace: a machine paused between a scan and its block, the simulator with it,
    sends no scan meanwhile, and its pause does not count against the block). The list stops at the
    first block that shows none."""
    ranges = [beam_ranges(scan, beams) for _, scan in sent]
    sent_times = [at for at, _ in sent]
    shown, after = [], -1
    for read, block in blocks:
        sent_before = bisect.bisect_right(sent_times, read)   # the scans sent up to the read
        found = next((i for i in range(after + 1, sent_before)
                      if (read - sent[i][0] <= window or sent_before - i <= window_scans)
                      and shows(block, ranges[i])), None)
        if found is None:
            break
        shown.append(found)
        after = found
    return shown


def _why_unshown(block, read, sent, beams, shown):
    """Why a block read at `read` shows no scan of its moment, the scans `shown` by the blocks
    before it taken."""
    same = [i for i, (_, scan) in enumerate(sent) if shows(block, beam_ranges(scan, beams))]
    if not same:
        return 'no scan sent had those ranges'
    nearest = min(same, key=lambda i: abs(read - sent[i][0]))
    age = read - sent[nearest][0]
    when = '%.3f s %s it' % (abs(age), 'before' if age >= 0 else 'after')
    if nearest in shown:
        return 'that scan, sent %s, was printed already by block %d' % (when, shown.index(nearest) + 1)
    if shown and nearest < shown[-1]:
        return 'the scan with those ranges, sent %s, came before the one block %d printed' % (when, len(shown))
    return 'the scan with those ranges was sent %s' % when


def printed_in_time(blocks, sent, beams, needed, window, window_scans=0):
    """At least `needed` blocks were printed, each the scan of the moment it was printed, each a
    later scan than the block before (shown_scans)."""
    shown = shown_scans(blocks, sent, beams, window, window_scans)
    if len(shown) < len(blocks):
        read, block = blocks[len(shown)]
        start = sent[0][0] if sent else read
        return Verdict(False, '%d scans printed; block %d, printed %.3f s after the first scan, shows no scan '
                       'of the %.3f s before it%s (it printed %s; %s)' % (
                           len(blocks), len(shown) + 1, read - start, window,
                           ' later than block %d\'s' % len(shown) if shown else '', ', '.join(block),
                           _why_unshown(block, read, sent, beams, shown)))
    lags = [read - sent[i][0] for (read, _), i in zip(blocks, shown)]
    seen = '%d scans printed (%d needed), each a later scan than the one before' % (len(blocks), needed)
    if lags:
        seen += ', printed %.1f to %.1f ms after it was sent' % (1000 * min(lags), 1000 * max(lags))
    return Verdict(len(blocks) >= needed, seen)
