"""The headings of a Markdown page and the anchors GitHub gives them, for the tests that follow a
link to a section (the docs' links, the check's "see docs/...#section")."""
import re
import unicodedata

_FENCE = re.compile(r'^ {0,3}(```|~~~)')
_HEADING = re.compile(r'^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$')
_LINK = re.compile(r'!?\[([^\]]*)\]\([^)]*\)')


def anchor_of(heading):
    """The anchor of one heading's text: a link keeps its text, lower case, every character but
    letters, digits, spaces, `-` and `_` dropped, spaces as `-`."""
    text = _LINK.sub(r'\1', heading).strip().lower()
    kept = ''.join(c for c in text if c in ' -_' or unicodedata.category(c)[0] in 'LN')
    return kept.replace(' ', '-')


def headings(markdown):
    """[(line index, level 1 to 6, anchor)] of the page's headings in order, none inside fenced
    code; a repeated anchor gets -1, -2, ... as on GitHub."""
    found, seen, fence = [], {}, None
    for number, line in enumerate(markdown.split('\n')):
        opening = _FENCE.match(line)
        if opening:
            if fence is None:
                fence = opening.group(1)
            elif opening.group(1) == fence:
                fence = None
            continue
        heading = _HEADING.match(line)
        if fence is not None or not heading:
            continue
        anchor = anchor_of(heading.group(2))
        count = seen.get(anchor, 0)
        seen[anchor] = count + 1
        found.append((number, len(heading.group(1)), anchor if not count else '%s-%d' % (anchor, count)))
    return found


def heading_anchors(markdown):
    """The anchors of the page's headings, in order."""
    return [anchor for _, _, anchor in headings(markdown)]
