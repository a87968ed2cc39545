"""The laser lines laser_data.py prints (the slide's five beams under a line of '='), and whether
they are ranges of scans the simulator published."""
import math

from course_checks.verdict import Verdict

LABELS = ['s1 [0]', 's2 [90]', 's3 [180]', 's4 [270]', 's5 [359]']
SEPARATOR = '=' * 10


def normalized(lines):
    """Output lines stripped, with the separator line of any length (the slide's is cut short) as
    SEPARATOR."""
    stripped = [line.strip() for line in lines]
    return [SEPARATOR if len(s) >= 3 and set(s) == {'='} else s for s in stripped]


def printed_blocks(lines):
    """The complete blocks printed with the slide's labels: lists of the 5 values (text). Anything
    else in the output (roslaunch, fake_tb3) is passed over."""
    blocks = []
    for start, line in enumerate(lines):
        block = lines[start + 1:start + 11]
        if line == SEPARATOR and block[0::2] == LABELS:
            blocks.append(block[1::2])
    return blocks


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


def unmatched_blocks(blocks, scans, beams):
    """The printed blocks that are no published scan's ranges at those beams."""
    published = [[scan.ranges[i] if i < len(scan.ranges) else math.nan for i in beams] for scan in scans]
    return [block for block in blocks
            if not any(all(same_range(p, s) for p, s in zip(block, ranges)) for ranges in published)]


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
