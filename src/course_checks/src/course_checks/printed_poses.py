"""Whether the poses a node printed are poses turtlesim published, judged against the poses a
recorder heard.

A recorder does not hear every pose: turtlesim publishes with a queue of one, so on a busy machine
a subscriber misses some. What it missed still lies on the turtle's path between two poses it
heard: turtlesim moves a turtle in fixed steps (turn by angular.z * dt, then move linear.x * dt
along the new heading), so while the velocities stay the same the positions are corners of a
regular polygon, on one circle (a straight line when it does not turn, one spot when it only
turns), and the heading turns by the same angle at each step. A printed pose is on the path when
it lies on that arc between two consecutive heard poses, at the heading turned in proportion,
within TOLERANCE (the poses are float32, printed with 6 decimals: about 1e-6 off).

Made-up poses lie nowhere on the path; a pose printed once and then again and again (constant)
or long after the turtle moved on (stale) lies on it, but falls behind the turtle. Pure numpy (no
rospy), so that test/unit/ checks it in milliseconds.
"""
import collections
import math

import numpy

TOLERANCE = 1e-4       # metres and radians: a hundred times what float32 and %f leave
MIN_SHARE = 0.9        # of the printed poses that must lie on the path (where velocities change
                       # between two heard poses, those in between are not on one arc)
MAX_GAP = 60           # steps of the path (turtlesim makes 62.5 a second): the most the printed
                       # poses may skip at once, or stay behind the last heard pose
SEARCH_AHEAD = 64      # steps looked at first from the last place (then the rest of the path)


def wrap(angle):
    """An angle (or array of angles) wrapped to [-pi, pi)."""
    return (numpy.asarray(angle, dtype=float) + math.pi) % (2 * math.pi) - math.pi


class Path:
    """The heard poses (rows of x, y, theta) as the turtle's path: poses that repeat the previous
    one (a turtle at rest) are left out, so each step of the path is one in which it moved or turned."""

    def __init__(self, heard):
        poses = numpy.asarray(heard, dtype=float)
        poses = poses[:, :3] if poses.size else numpy.zeros((0, 3))
        moved = numpy.ones(len(poses), dtype=bool)
        moved[1:] = numpy.abs(numpy.diff(poses, axis=0)).max(axis=1) > 0
        self.poses = poses[moved]
        start, end = self.poses[:-1], self.poses[1:]
        self.chord = end[:, :2] - start[:, :2]
        self.length = numpy.hypot(self.chord[:, 0], self.chord[:, 1])
        self.direction = numpy.arctan2(self.chord[:, 1], self.chord[:, 0])
        self.turn = wrap(end[:, 2] - start[:, 2])

    @property
    def steps(self):
        return max(len(self.poses) - 1, 0)

    def place(self, pose, first=0.0, tolerance=TOLERANCE):
        """Where on the path the pose (x, y, theta) lies, at `first` or after: the index of a heard
        pose, or i + t (0 < t < 1) between heard poses i and i + 1; None when it lies nowhere there."""
        if self.steps == 0:   # one pose heard (or none): the turtle never moved
            return 0.0 if len(self.poses) and _close(pose, self.poses[0], tolerance) else None
        start = min(int(first), self.steps - 1)
        for end in (min(start + SEARCH_AHEAD, self.steps), self.steps):
            found = self._place_between(numpy.asarray(pose, dtype=float), start, end, first, tolerance)
            if found is not None:
                return found
            start = end
        return None

    def _place_between(self, pose, begin, end, first, tolerance):
        """The first place on the steps begin..end-1 (at `first` or after) where the pose lies."""
        if begin >= end:
            return None
        a = self.poses[begin:end]
        length, direction, turn = self.length[begin:end], self.direction[begin:end], self.turn[begin:end]
        offset = pose[:2] - a[:, :2]
        moving = length > tolerance
        along = offset[:, 0] * numpy.cos(direction) + offset[:, 1] * numpy.sin(direction)
        arc = numpy.abs(turn) > 1e-9
        with numpy.errstate(divide='ignore', invalid='ignore'):
            # How far along the step: from the position where the turtle moved (on an arc, its
            # projection on the chord is (sin(t turn - turn/2) + sin(turn/2)) / (2 sin(turn/2)) of
            # it), from the heading where it only turned.
            chord_share = numpy.where(moving, along / numpy.where(moving, length, 1.0), 0.0)
            on_arc = (numpy.arcsin(numpy.clip((2 * chord_share - 1) * numpy.sin(turn / 2), -1, 1)) + turn / 2) / turn
            t = numpy.where(moving, numpy.where(arc, on_arc, chord_share),
                            numpy.where(arc, wrap(pose[2] - a[:, 2]) / turn, 0.0))
            t = numpy.clip(numpy.nan_to_num(t), 0.0, 1.0)
            # The point at share t of the arc: its chord from the start is sin(t turn/2) / sin(turn/2)
            # of the whole chord, turned by (t - 1) turn / 2 from it.
            reach = numpy.where(arc, numpy.sin(t * turn / 2) / numpy.where(arc, numpy.sin(turn / 2), 1.0), t) * length
            heading = direction + numpy.where(arc, (t - 1) * turn / 2, 0.0)
        expected_x = a[:, 0] + reach * numpy.cos(heading)
        expected_y = a[:, 1] + reach * numpy.sin(heading)
        near = numpy.hypot(pose[0] - expected_x, pose[1] - expected_y) <= tolerance
        turned = numpy.abs(wrap(pose[2] - (a[:, 2] + t * turn))) <= tolerance
        places = begin + numpy.arange(len(t)) + t
        hits = numpy.nonzero(near & turned & (places >= first - 1e-9))[0]
        return float(places[hits[0]]) if len(hits) else None


def _close(pose, other, tolerance):
    difference = numpy.abs(numpy.asarray(pose[:3], dtype=float) - other[:3])
    difference[2] = abs(float(wrap(difference[2])))
    return difference.max() <= tolerance


Judgement = collections.namedtuple('Judgement', [
    'judged',        # printed poses judged (those printed before the recording began left out)
    'skipped',       # printed before the recorder began to listen, or after its last pose
    'on_path',       # of the judged, how many lie on the path
    'between',       # of those, how many only between two heard poses (the recorder missed them)
    'unexplained',   # the judged poses that lie nowhere on the path (at or after the one before)
    'largest_gap',   # the most steps of the path between two printed poses in a row
    'behind',        # steps of the path after the last printed pose
    'steps'])        # steps of the heard path


def judge(printed, heard, tolerance=TOLERANCE, max_gap=MAX_GAP):
    """Places the printed poses (rows of x, y, theta, numbers or their text) on the heard path
    (rows of x, y, theta, ...), in the order they were printed: each at or after the one before."""
    path = Path(heard)
    printed = [tuple(float(value) for value in pose[:3]) for pose in printed]
    # A node prints from its start; the recorder may begin to listen a little later. What was
    # printed before the first pose found on the start of the path cannot be judged.
    first = 0
    for index, pose in enumerate(printed):
        found = path.place(pose, 0.0, tolerance)
        if found is not None and found <= max_gap:
            first = index
            break
    placed, unexplained, last = [], [], 0.0
    for index in range(first, len(printed)):
        found = path.place(printed[index], last, tolerance)
        if found is None:
            unexplained.append(index)
            continue
        if abs(found - round(found)) < 1e-3:   # one of the heard poses (give or take float32)
            found = float(round(found))
        placed.append((index, found))
        last = found
    end = len(printed)
    # Likewise the recorder may not have heard yet the last poses printed, after the end of its path.
    if placed and path.steps - placed[-1][1] <= max_gap and len(printed) - 1 - placed[-1][0] <= max_gap:
        end = placed[-1][0] + 1
        unexplained = [index for index in unexplained if index < end]
    places = [place for _, place in placed]
    gaps = numpy.diff(places) if len(places) > 1 else [0.0]
    return Judgement(judged=end - first, skipped=first + len(printed) - end, on_path=len(places),
                     between=sum(place != int(place) for place in places),
                     unexplained=[printed[index] for index in unexplained],
                     largest_gap=int(round(max(gaps))),
                     behind=int(round(path.steps - places[-1])) if places else path.steps, steps=path.steps)


def _pose_text(pose):
    return '(%s)' % ', '.join('%.6f' % value for value in pose)


def problem(judgement, min_share=MIN_SHARE, max_gap=MAX_GAP):
    """What is wrong with the printed poses, as a sentence; '' when they follow the turtle."""
    if not judgement.steps and not judgement.on_path:
        return 'no pose heard from turtlesim to compare with'
    if not judgement.judged:
        return 'no pose printed'
    if judgement.on_path < min_share * judgement.judged:
        return ('%d of the %d printed poses lie nowhere on the path turtlesim published (the first: %s); '
                'at least %d %% must lie on it' % (len(judgement.unexplained), judgement.judged,
                                                   _pose_text(judgement.unexplained[0]), round(100 * min_share)))
    if judgement.largest_gap > max_gap:
        return ('the printed poses skipped %d steps of the turtle\'s path at once (at most %d: about a second)'
                % (judgement.largest_gap, max_gap))
    if judgement.behind > max_gap:
        return ('the last printed pose is %d steps of the turtle\'s path behind its last pose (at most %d: '
                'about a second): the printed pose does not follow the turtle' % (judgement.behind, max_gap))
    return ''


def summary(judgement):
    """The judgement in a few words, for a report."""
    return '%d printed poses, %d on the path turtlesim published (%d between poses the recorder missed)' % (
        judgement.judged, judgement.on_path, judgement.between)
