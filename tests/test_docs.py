"""The documentation a reader follows: a short front page, links and pictures that lead somewhere,
and a README in every package the labs table sends a student to."""
import os
import re
import subprocess
import sys

import pytest

from course_testing.markdown import heading_anchors

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FRONT_PAGE = os.path.join(ROOT, 'README.md')
FRONT_PAGE_MAX_LINES = 150
# Drafts waiting to be merged into other pages; their links are written for where they will go.
DRAFTS = 'docs/_handover/'
# Folders that are built or written by the project, never documentation of it.
NOT_SOURCES = {'.git', 'build', 'devel', 'install', 'output', '__pycache__'}

FENCE = re.compile(r'^(```|~~~).*?^\1[^\n]*$', re.M | re.S)
CODE_SPAN = re.compile(r'(`+).+?\1', re.S)
INLINE_LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
REFERENCE_DEFINITION = re.compile(r'^ {0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+"[^"]*")?\s*$', re.M)
HTML_TARGET = re.compile(r'<(?:img|a)\b[^>]*?\b(?:src|href)\s*=\s*"([^"]+)"', re.I)


def markdown_files():
    """Every tracked *.md (relative paths); without git (the Docker image has no .git), every *.md
    outside the folders the build writes."""
    try:
        listed = subprocess.run(['git', '-C', ROOT, 'ls-files', '-z', '--', '*.md'],
                                capture_output=True, check=True).stdout.decode()
        files = [path for path in listed.split('\0') if path]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for folder, subfolders, names in os.walk(ROOT):
            subfolders[:] = sorted(d for d in subfolders if d not in NOT_SOURCES)
            files += [os.path.relpath(os.path.join(folder, n), ROOT) for n in sorted(names)
                      if n.endswith('.md')]
    return [path for path in files if not path.startswith(DRAFTS)]


def prose(text):
    """The text a reader sees as prose: code blocks and code spans blanked out."""
    return CODE_SPAN.sub('', FENCE.sub('', text))


def link_targets(text):
    text = prose(text)
    return (INLINE_LINK.findall(text) + REFERENCE_DEFINITION.findall(text)
            + HTML_TARGET.findall(text))


def is_external(target):
    return re.match(r'^[a-z][a-z0-9+.-]*:', target, re.I) is not None


def anchors(path):
    with open(path, encoding='utf-8') as page:
        return set(heading_anchors(page.read()))


def broken_links(markdown_path):
    """The links and pictures of one page that lead nowhere, each with the reason."""
    page = os.path.join(ROOT, markdown_path)
    with open(page, encoding='utf-8') as handle:
        targets = link_targets(handle.read())
    broken = []
    for target in targets:
        if is_external(target):
            continue
        path, _, fragment = target.partition('#')
        if path.startswith('/'):
            broken.append('%s: absolute path (not there in a clone)' % target)
            continue
        resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
        if not os.path.exists(resolved):
            broken.append('%s: no such file' % target)
        elif fragment and resolved.endswith('.md') and fragment not in anchors(resolved):
            broken.append('%s: no heading with that anchor' % target)
    return broken


def front_page():
    with open(FRONT_PAGE, encoding='utf-8') as page:
        return page.read()


def labs_table(text):
    """The rows of the first table under the heading `## The labs`, without its header."""
    section = text.split('\n## The labs', 1)[1].split('\n## ', 1)[0].splitlines()
    first = next(i for i, line in enumerate(section) if line.startswith('|'))
    table = []
    for line in section[first:]:
        if not line.startswith('|'):
            break
        table.append(line)
    return [line for line in table[1:] if not re.match(r'^\|[\s|:-]+\|$', line)]


def test_the_front_page_is_short():
    lines = front_page().count('\n')
    assert lines < FRONT_PAGE_MAX_LINES, (
        'README.md has %d lines: the front page stays under %d; move detail to a package README '
        'or docs/' % (lines, FRONT_PAGE_MAX_LINES))


@pytest.mark.parametrize('markdown_path', markdown_files())
def test_every_link_and_picture_leads_somewhere(markdown_path):
    assert broken_links(markdown_path) == []


def test_every_package_of_the_labs_table_has_a_readme():
    rows = labs_table(front_page())
    assert len(rows) >= 7, 'the labs table has %d rows' % len(rows)
    packages = set()
    for row in rows:
        readmes = [target.partition('#')[0] for target in INLINE_LINK.findall(prose(row))
                   if target.startswith('src/')]
        assert readmes, 'a row of the labs table links to no package README: %s' % row
        packages.update(readmes)
    for readme in sorted(packages):
        assert readme.endswith('README.md'), 'the labs table links to %s, not a README' % readme
        assert os.path.isfile(os.path.join(ROOT, readme)), '%s is missing' % readme


def test_every_course_package_is_in_the_labs_table():
    linked = ' '.join(labs_table(front_page()))
    for package in ('src/turtlesim', 'src/my_turtle', 'src/ros_exercises', 'src/fake_tb3',
                    'src/move_turtlebot3', 'src/compat'):
        assert '(%s/README.md' % package in linked, '%s is not in the labs table' % package


def test_every_picture_is_shown_somewhere():
    shown = set()
    for markdown_path in markdown_files():
        page = os.path.join(ROOT, markdown_path)
        with open(page, encoding='utf-8') as handle:
            for target in link_targets(handle.read()):
                if not is_external(target):
                    shown.add(os.path.normpath(os.path.join(os.path.dirname(page),
                                                            target.partition('#')[0])))
    images = os.path.join(ROOT, 'docs', 'images')
    unused = sorted(name for name in os.listdir(images)
                    if os.path.join(images, name) not in shown)
    assert unused == [], 'pictures in docs/images that no page shows (stale?): %s' % unused


# The checker itself, on pages made up for it: it must find what is broken and pass what is not.

def test_the_checker_finds_broken_links_and_pictures(tmp_path, monkeypatch):
    (tmp_path / 'docs').mkdir()
    (tmp_path / 'docs' / 'there.md').write_text('# A page\n\n## Its part, `code` and all\n')
    (tmp_path / 'picture.png').write_bytes(b'')
    (tmp_path / 'page.md').write_text(
        '[ok](docs/there.md) ![ok](picture.png) [ok](docs/there.md#its-part-code-and-all)\n'
        '[ok](https://example.org/x) [ok](#a-heading)\n\n# A heading\n\n'
        '`[not a link](nowhere.md)`\n\n```\n![not a picture](nowhere.png)\n```\n'
        '[missing](docs/gone.md) ![missing](gone.png) [bad anchor](docs/there.md#no-such-part)\n'
        '[absolute](/etc/hostname)\n\n[ref]: docs/also-gone.md\n<img src="gone-too.png">\n')
    monkeypatch.setattr(sys.modules[__name__], "ROOT", str(tmp_path))
    assert sorted(broken_links('page.md')) == sorted([
        'docs/gone.md: no such file',
        'gone.png: no such file',
        'docs/there.md#no-such-part: no heading with that anchor',
        '/etc/hostname: absolute path (not there in a clone)',
        'docs/also-gone.md: no such file',
        'gone-too.png: no such file',
    ])
