"""Each run of report.html played back in the page: a run's rosbag (and the moments its checks
judged, <run>.marks.json) turned into the frames the live view's server sends (course_web.frames:
the same scenes, the same frames, drawn by the same scene.js), written beside the bag as
<run>.replay.js, a script that sets `window.courseReplay` (a page opened from file:// cannot fetch()
a file, it can load a script). The player (course_web's web/replay.html, replay.js and the drawing
they share with the live view) is copied once into the grading's folder, _player/, and report.html
shows it in a frame per run: the folder alone is the whole report, to zip and send, offline.

The frames are sampled as a page would be sent them: at most FRAMES_PER_SECOND of the run's time,
each one what changed since the one before (frames.Scenes from its cursor), and now and then a whole
frame (what the server sends a page that connects) from which the player seeks. A run whose data
would pass MAX_BYTES keeps fewer scans, then fewer frames per second.
"""
import base64
import html
import json
import math
import os
import zlib
from urllib.parse import quote

import rosbag
import rospkg

from course_grader.bags import BAG_SUFFIX, MARKS_SUFFIX
from course_web.frames import NEW_PAGE, Scenes
from course_web.tb3_scene import odometry_fields
from fake_tb3.world import load_world
from turtlesim.canvas import CANVAS_PX
from turtlesim.world import DEFAULT_BACKGROUND, DEFAULT_PEN_COLOR, DEFAULT_PEN_WIDTH, PX_PER_METER, WORLD_SIZE

FRAMES_PER_SECOND = 25
MIN_FRAMES_PER_SECOND = 5
KEY_SECONDS = 2.0    # a whole frame at least this often (seeking replays the frames after it)
MAX_KEYS = 30        # and at most this many in a run (a longer run gets them further apart)
MAX_BYTES = 2000000  # a run's data at most, about: then fewer scans, then fewer frames a second
MAX_MARK_TEXT = 300
DATA_SUFFIX = '.replay.js'
PLAYER_FOLDER = '_player'
PLAYER_FILES = ('replay.html', 'replay.js', 'replay.css', 'scene.js', 'view.css')


class ReplayError(ValueError):
    """A bag that cannot be played back; the text is one sentence for the report."""


# ---------------------------------------------------------------- the bag
def read_bag(path):
    """[(seconds, topic, message type, message)] of a bag, in time order."""
    with rosbag.Bag(path) as bag:
        types = {topic: info.msg_type for topic, info in bag.get_type_and_topic_info().topics.items()}
        return [(stamp.to_sec(), topic, types[topic], message)
                for topic, message, stamp in bag.read_messages()]


class _Turtlesim:
    """turtlesim's ~scene messages made from what its bag holds (course_grader.bags): each move
    with the pen down draws the line turtlesim draws (from the last pose to this one, in its pen),
    the canvas is filled at the start and at each /clear, and the turtles killed leave."""

    def __init__(self, scene):
        self.scene, self.seq, self.started = scene, 0, False
        self.background = DEFAULT_BACKGROUND
        self.poses, self.pens, self.icons = {}, {}, {}

    def _send(self, stamp, ops=(), turtles=(), gone=()):
        message = {'seq': self.seq, 'stamp': stamp, 'ops': list(ops), 'turtles': list(turtles), 'gone': list(gone)}
        if not self.started:
            pixels = bytes(self.background) * (CANVAS_PX * CANVAS_PX)
            message['canvas'] = {'width': CANVAS_PX, 'height': CANVAS_PX,
                                 'rgb_zlib_base64': base64.b64encode(zlib.compress(pixels)).decode('ascii')}
            self.started = True
        self.scene.apply(message)
        self.seq += 1

    def pose(self, stamp, name, x, y, theta):
        if not all(map(math.isfinite, (x, y, theta))):
            return
        icon = self.icons.setdefault(name, len(self.icons))
        ops = []
        last = self.poses.get(name)
        (r, g, b), width, off = self.pens.get(name, (DEFAULT_PEN_COLOR, DEFAULT_PEN_WIDTH, False))
        if last is not None and not off and last != (x, y):
            ops.append(['line', last[0] * PX_PER_METER, (WORLD_SIZE - last[1]) * PX_PER_METER,
                        x * PX_PER_METER, (WORLD_SIZE - y) * PX_PER_METER, r, g, b, width])
        self.poses[name] = (x, y)
        self._send(stamp, ops, [[name, round(x, 4), round(y, 4), round(theta, 4), icon]])

    def pen(self, name, r, g, b, width, off):
        if off:
            colour, old_width, _ = self.pens.get(name, (DEFAULT_PEN_COLOR, DEFAULT_PEN_WIDTH, False))
            self.pens[name] = (colour, old_width, True)
        else:
            self.pens[name] = ((r, g, b), width or 1, False)   # width 0 is 1, as turtlesim has it

    def fill(self, stamp, background):
        if self.started:
            self._send(stamp, [['fill'] + background])
        else:
            self.background = tuple(background)

    def roster(self, stamp, names):
        gone = [name for name in self.poses if name not in names]
        for name in gone:
            del self.poses[name]
        if gone and self.started:
            self._send(stamp, gone=gone)


def _json_fields(message):
    fields = json.loads(message.data)
    if not isinstance(fields, dict):
        raise ValueError('expected a JSON object, got %r' % message.data[:60])
    return fields


def _events(messages, scenes):
    """[(seconds, what to apply to the scenes[, 'scan'])] of the bag's messages (the topics of
    course_grader.bags), and the first drawable moment (a pose): the run's time 0."""
    events, start = [], None
    turtlesim = _Turtlesim(scenes.turtlesim)
    run = next((_json_fields(message) for _, topic, _, message in messages if topic == '/fake_tb3/run'), {})
    odom_topic = None
    for stamp, topic, message_type, message in messages:
        names = topic.strip('/').split('/')
        last, owner = names[-1], names[-2] if len(names) > 1 else ''
        if message_type == 'turtlesim/Pose':
            events.append((stamp, lambda s=stamp, t=owner or 'turtle1', m=message: turtlesim.pose(s, t, m.x, m.y, m.theta)))
            start = stamp if start is None else start
        elif message_type == 'turtlesim/SetPenRequest' and owner:
            events.append((stamp, lambda t=owner, m=message: turtlesim.pen(t, m.r, m.g, m.b, m.width, m.off)))
        elif message_type == 'std_msgs/String' and last == 'canvas':
            events.append((stamp, lambda s=stamp, f=_json_fields(message): turtlesim.fill(
                s, [int(c) for c in f['background']])))
        elif message_type == 'std_msgs/String' and last == 'turtles':
            events.append((stamp, lambda s=stamp, f=_json_fields(message): turtlesim.roster(
                s, {str(name).rsplit('/', 1)[-1] for name in f['names']})))
        elif message_type == 'nav_msgs/Odometry' and topic == (odom_topic or topic):
            if odom_topic is None:   # one robot: the first odometry's (its scan beside it)
                odom_topic = topic
                scenes.tb3.start(load_world(run.get('world') or 'empty'), run.get('model') or 'burger')
            events.append((stamp, lambda m=message: scenes.tb3.on_odom(*odometry_fields(m))))
            start = stamp if start is None else start
        elif message_type == 'sensor_msgs/LaserScan' and topic[:-len('scan')] == (odom_topic or '/odom')[:-len('odom')]:
            events.append((stamp, lambda m=message: scenes.tb3.on_scan(
                m.ranges, m.angle_min, m.angle_increment, m.range_min, m.range_max), 'scan'))
    if start is None:
        raise ReplayError('it holds no pose of a turtle (turtlesim/Pose) nor odometry (nav_msgs/Odometry) to show')
    return events, start


def _frames(messages, frames_per_second, scan_stride, key_spread):
    """(times, frame texts, {index: whole frame text}, the run's time 0, seconds between whole
    frames) of one sampling: a whole frame every KEY_SECONDS (or the run's MAX_KEYS-th part, when
    longer) times key_spread."""
    scenes = Scenes()
    events, start = _events(messages, scenes)
    period = 1.0 / frames_per_second
    end = max(stamp for stamp, *_ in events)
    key_seconds = max(KEY_SECONDS, (end - start) / MAX_KEYS) * key_spread
    times, frames, keys = [], [], {}
    cursor, last_key, scans = NEW_PAGE, None, 0

    def sample(at):
        nonlocal cursor, last_key
        text, cursor = scenes.frame_for(cursor)
        if text is None:
            return
        if not frames or at - last_key >= key_seconds:
            last_key = at
            if frames:
                keys[len(frames)] = scenes.frame_for(NEW_PAGE)[0]
        times.append(round(at, 3))
        frames.append(text)

    def drawable():
        return scenes.turtlesim.present or scenes.tb3.pose is not None

    bucket, pending = None, None   # the sampling period of the last event; its time, when not sent yet
    for stamp, apply, *kind in events:
        at = max(0.0, stamp - start)
        if kind:   # a scan
            scans += 1
            if (scans - 1) % scan_stride:
                continue
        here = int(at / period)
        if not frames and at > 0 and drawable():
            sample(0.0)   # the first picture: all that came at the run's start
        elif pending is not None and here != bucket:
            sample(pending)
            pending = None
        apply()
        bucket = here
        if frames:
            pending = at
    if pending is not None or not frames:
        sample(pending or 0.0)
    return times, frames, keys, start, key_seconds


def replay_data(messages, marks=()):
    """The player's data of a run: {duration, times, frames (JSON texts), keys ({index: whole frame
    text}), marks (in the player's seconds), frames_per_second, scan_stride}, thinned to about
    MAX_BYTES: whole frames further apart while they are half of it (a long path in each), scans
    (down to one in 8), then frames a second (down to 5). `marks` count in the bag's own
    (simulated) time, as course_grader.bags writes them."""
    frames_per_second, scan_stride, key_spread = FRAMES_PER_SECOND, 1, 1
    while True:
        times, frames, keys, start, key_seconds = _frames(messages, frames_per_second, scan_stride, key_spread)
        key_bytes = sum(map(len, keys.values()))
        if sum(map(len, frames)) + key_bytes <= MAX_BYTES:
            break
        if key_bytes > MAX_BYTES // 2 and keys:
            key_spread *= 2
        elif scan_stride < 8:
            scan_stride *= 2
        elif frames_per_second > MIN_FRAMES_PER_SECOND:
            frames_per_second = max(MIN_FRAMES_PER_SECOND, frames_per_second // 2)
        elif keys:
            key_spread *= 2
        else:
            break   # as thin as it goes
    return {'duration': times[-1] if times else 0.0, 'times': times, 'frames': frames, 'keys': keys,
            'marks': [dict(mark, t=round(min(max(0.0, mark['t'] - start), times[-1] if times else 0.0), 3))
                      for mark in marks],
            'frames_per_second': frames_per_second, 'scan_stride': scan_stride, 'key_seconds': round(key_seconds, 3)}


def read_marks(path):
    """[{t, what, criterion}] of a <run>.marks.json, by time (none when it is missing or not of
    that form)."""
    try:
        with open(path, encoding='utf-8') as stream:
            entries = json.load(stream)
    except (OSError, ValueError):
        return []
    marks = []
    for entry in entries if isinstance(entries, list) else []:
        if isinstance(entry, dict) and isinstance(entry.get('t'), (int, float)) and math.isfinite(entry['t']):
            marks.append({'t': float(entry['t']), 'what': str(entry.get('what', ''))[:MAX_MARK_TEXT],
                          'criterion': str(entry.get('criterion', ''))[:MAX_MARK_TEXT]})
    return sorted(marks, key=lambda mark: mark['t'])


def script_text(data):
    """The .replay.js of a run's data: it sets window.courseReplay (JSON; the frames as made)."""
    head = json.dumps({k: v for k, v in data.items() if k not in ('frames', 'keys')}, separators=(',', ':'))
    frames = ','.join(data['frames'])
    keys = ','.join('[%d,%s]' % (index, text) for index, text in sorted(data['keys'].items()))
    return 'window.courseReplay = %s;\nwindow.courseReplay.frames = [%s];\nwindow.courseReplay.keys = [%s];\n' % (
        head, frames, keys)


def write_replay(bag_path):
    """<run>.replay.js beside <run>.bag (with <run>.marks.json's marks); its size in bytes.
    ReplayError with one sentence when the bag cannot be played back."""
    base = bag_path[:-len(BAG_SUFFIX)]
    try:
        messages = read_bag(bag_path)
        if not messages:
            raise ReplayError('its bag holds no messages')
        data = replay_data(messages, read_marks(base + MARKS_SUFFIX))
    except ReplayError:
        raise
    except Exception as error:   # whatever a broken bag raises: the report says it, the grade stands
        raise ReplayError('its bag cannot be read (%s: %s)' % (type(error).__name__, str(error)[:200])) from None
    data['run'] = os.path.basename(base)
    text = script_text(data)
    with open(base + DATA_SUFFIX, 'w', encoding='utf-8') as stream:
        stream.write(text)
    return len(text.encode('utf-8'))


# ---------------------------------------------------------------- the report
def web_dir():
    """course_web's web/ folder: the live view's files and the player's."""
    return os.path.join(rospkg.RosPack().get_path('course_web'), 'web')


def install_player(out_dir):
    """The player's files in out_dir/_player/ (copied when missing or changed)."""
    folder = os.path.join(out_dir, PLAYER_FOLDER)
    os.makedirs(folder, exist_ok=True)
    source = web_dir()
    for name in PLAYER_FILES:
        with open(os.path.join(source, name), 'rb') as stream:
            wanted = stream.read()
        target = os.path.join(folder, name)
        try:
            with open(target, 'rb') as stream:
                if stream.read() == wanted:
                    continue
        except OSError:
            pass
        with open(target, 'wb') as stream:
            stream.write(wanted)


def runs_html(out_dir, folder):
    """The players of a student's runs (its folder's <run>.bag files) for report.html: each run's
    .replay.js made (when older than its bag), the player installed, a frame per run; a bag that
    cannot be played back is one sentence instead. '' without bags."""
    student_dir = os.path.join(out_dir, folder)
    bags = sorted(name for name in os.listdir(student_dir) if name.endswith(BAG_SUFFIX)) \
        if os.path.isdir(student_dir) else []
    if not bags:
        return ''
    install_player(out_dir)
    esc = html.escape
    parts = ['<div class="replays">']
    for bag in bags:
        run = bag[:-len(BAG_SUFFIX)]
        bag_path = os.path.join(student_dir, bag)
        try:
            if _stale(os.path.join(student_dir, run)):
                write_replay(bag_path)
        except ReplayError as error:
            parts.append('<p class="replay-error">The run %s cannot be replayed: %s.</p>' % (esc(run), esc(str(error))))
            continue
        address = '%s/replay.html#%s/%s' % (PLAYER_FOLDER, _quote(folder), _quote(run))
        parts.append('<figure class="replay"><figcaption>%s, replayed</figcaption><iframe class="replay" '
                     'loading="lazy" src="%s" title="%s of %s, replayed"></iframe></figure>'
                     % (esc(run), esc(address), esc(run), esc(folder)))
    parts.append('</div>')
    return '\n'.join(parts)


def _stale(base):
    """Whether <base>.replay.js is missing or older than its bag or marks."""
    try:
        made = os.path.getmtime(base + DATA_SUFFIX)
    except OSError:
        return True
    return any(os.path.exists(base + suffix) and os.path.getmtime(base + suffix) > made
               for suffix in (BAG_SUFFIX, MARKS_SUFFIX))


def _quote(name):
    return quote(name, safe='')


# What report.html needs once for its players: their frames' size, and each frame's height as its
# page tells it (frames from file:// are of another origin: only a message crosses).
PAGE_PARTS = '''<style>
figure.replay { margin: 0.5em 0; max-width: 560px; }
iframe.replay { box-sizing: border-box; width: 100%; height: 720px; border: 1px solid #ccc; }
.replay-error { color: #a11; }
</style>
<script>
addEventListener('message', function (event) {
  var height = event.data && event.data.courseReplayHeight;
  if (typeof height !== 'number') return;
  document.querySelectorAll('iframe.replay').forEach(function (frame) {
    if (frame.contentWindow === event.source) frame.style.height = Math.ceil(height) + 'px';
  });
});
</script>'''
