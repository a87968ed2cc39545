from course_testing.markdown import anchor_of, heading_anchors, headings
from course_testing.verdicts import masked_figures


def test_heading_anchors_are_githubs():
    page = ('# Title\n## 1. The whole paste indented\n### `lin_vel_` was not declared\n'
            '### `turtlesim/Pose.h: No such file or directory`\n```\n# not a heading\n```\n## chmod +x\n'
            '## chmod +x ##\n### See [the lab](other.md#part) first\n## Départ à 0,5 m/s\n')
    assert heading_anchors(page) == ['title', '1-the-whole-paste-indented', 'lin_vel_-was-not-declared',
                                     'turtlesimposeh-no-such-file-or-directory', 'chmod-x', 'chmod-x-1',
                                     'see-the-lab-first', 'départ-à-05-ms']


def test_headings_give_their_lines_and_levels_and_fences_hide_theirs():
    page = '# A\n~~~\n## not one\n```\n## still not\n~~~\ntext\n   ## B ##\n    ## code\n### C'
    assert headings(page) == [(0, 1, 'a'), (7, 2, 'b'), (9, 3, 'c')]
    assert headings('#no space\n####### seven\n') == []
    assert anchor_of('  Mixed `Case` & Punctuation!  ') == 'mixed-case--punctuation'
    assert anchor_of('What survives what (measured)') == 'what-survives-what-measured'
    assert anchor_of('fake_tb3: how it behaves, and where it differs from Gazebo') == \
        'fake_tb3-how-it-behaves-and-where-it-differs-from-gazebo'
    assert anchor_of('Obstacle avoidance that keeps going: `wander.py`') == \
        'obstacle-avoidance-that-keeps-going-wanderpy'


def test_masked_figures_keep_the_words():
    assert masked_figures('stopped 0.446 m from the wall at x -0.800 m, 3 collisions') == \
        'stopped # m from the wall at x # m, # collisions'
    assert masked_figures('no figure') == 'no figure'
