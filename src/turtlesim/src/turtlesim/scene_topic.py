"""~scene: what the canvas shows, for a viewer such as course_web, published only while one listens.

Pen colours and widths, /clear and the ~background_* parameters change what turtlesim draws but
appear on no topic; this topic carries the drawing itself. std_msgs/String holding JSON, at most one
message per tick, sent when something changed:

  {"seq": n,                      # +1 per message: a gap means the viewer lost messages
   "stamp": wall time (s) of the tick,
   "ops": [["fill", r, g, b] | ["line", x0, y0, x1, y1, r, g, b, width], ...],
                                  # in drawing order; pixel coordinates of the 500x500 canvas
   "turtles": [[name, x, y, theta, icon], ...],   # metres, y up, as turtlesim/Pose: the turtles
                                  # spawned, moved or turned since the previous message (all of
                                  # them in a message with a canvas)
   "gone": [name, ...],           # killed since the previous message (only when some were)
   "canvas": {"width": w, "height": h, "rgb_zlib_base64": ...}}   # the path layer (no turtles),
                                  # first message after a subscriber connected; ops follow it

With nobody subscribed it costs one attribute test per drawn line and one connection count per tick;
with a viewer, a tick where one turtle of a hundred moves sends that one. The tick thread writes the
message to each viewer's socket itself, without waiting (course_common.batched_writes): no writer
thread to wake at every tick (the turtles' poses and colours are written the same way, and
after_tick() sends them too).
"""
import base64
import json
import time
import zlib

import rospy
from std_msgs.msg import String

from course_common import batched_writes

QUEUE_SIZE = 100  # 1.6 s of ticks: a viewer further behind sees a seq gap and resubscribes


class _SnapshotOnConnect(rospy.SubscribeListener):
    def __init__(self, scene):
        super().__init__()
        self.scene = scene

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        self.scene.snapshot_wanted = True


class SceneTopic:
    """Records the canvas' drawing calls and publishes them, with the turtles, after each tick."""

    def __init__(self, world):
        self.world = world
        self.recording = False
        self.snapshot_wanted = False
        self._ops = []
        self._seq = 0
        self._revision = None
        self._sent = {}  # name -> (x, y, theta, icon) last sent
        canvas = world.canvas
        fill, draw_line = canvas.fill, canvas.draw_line

        def recorded_fill(color):
            fill(color)
            if self.recording:
                self._ops.append(['fill'] + [int(c) for c in color])

        def recorded_draw_line(x0, y0, x1, y1, color, width):
            draw_line(x0, y0, x1, y1, color, width)
            if self.recording:
                self._ops.append(['line', x0, y0, x1, y1] + [int(c) for c in color] + [int(width)])

        canvas.fill, canvas.draw_line = recorded_fill, recorded_draw_line
        self.publisher = rospy.Publisher('~scene', String, queue_size=QUEUE_SIZE,
                                         subscriber_listener=_SnapshotOnConnect(self))
        batched_writes.batch(self.publisher)
        self._writes = batched_writes.WriterTurns()

    def after_tick(self):
        """In the tick thread, the only one that changes the world: publish what this tick drew,
        and hand what the viewers' sockets have not taken yet to them."""
        self._publish_changes()
        self._writes.flush()

    def _publish_changes(self):
        if not batched_writes.subscribed(self.publisher):
            self.recording = False
            self._ops = []
            return
        message = {}
        if self.snapshot_wanted or not self.recording:
            self.snapshot_wanted = False
            pixels = self.world.canvas.pixels
            message['canvas'] = {'height': pixels.shape[0], 'width': pixels.shape[1],
                                 'rgb_zlib_base64': base64.b64encode(
                                     zlib.compress(pixels.tobytes(), 1)).decode('ascii')}
            self._ops = []
            self._revision = None
            self._sent = {}
        self.recording = True
        if not (message or self._ops or self.world.revision != self._revision):
            return
        self._revision = self.world.revision
        changed, gone = self._turtle_changes()
        if not (message or self._ops or changed or gone):
            return
        self._seq += 1
        message.update(seq=self._seq, stamp=time.time(), ops=self._ops, turtles=changed)
        if gone:
            message['gone'] = gone
        self._ops = []
        batched_writes.publish(self.publisher, String(json.dumps(message, separators=(',', ':'))))

    def _turtle_changes(self):
        """([name, x, y, theta, icon] of each turtle unlike what was last sent, names of the killed)."""
        sent, now, changed, spawned = self._sent, {}, [], False
        for turtle in self.world.turtles():
            state = (turtle.x, turtle.y, turtle.theta, turtle.icon)
            before = sent.get(turtle.name)
            if before != state:
                changed.append([turtle.name, state[0], state[1], state[2], state[3]])
                spawned = spawned or before is None
            now[turtle.name] = state
        gone = [name for name in sent if name not in now] if spawned or len(now) != len(sent) else []
        self._sent = now
        return changed, gone
