"""~scene: what the canvas shows, for a viewer such as course_web, published only while one listens.

Pen colours and widths, /clear and the ~background_* parameters change what turtlesim draws but
appear on no topic; this topic carries the drawing itself. std_msgs/String holding JSON, at most one
message per tick, sent when something changed:

  {"seq": n,                      # +1 per message: a gap means the viewer lost messages
   "stamp": wall time (s) of the tick,
   "ops": [["fill", r, g, b] | ["line", x0, y0, x1, y1, r, g, b, width], ...],
                                  # in drawing order; pixel coordinates of the 500x500 canvas
   "turtles": [[name, x, y, theta, icon], ...],   # metres, y up, as turtlesim/Pose
   "canvas": {"width": w, "height": h, "rgb_zlib_base64": ...}}   # the path layer (no turtles),
                                  # first message after a subscriber connected; ops follow it

With nobody subscribed it costs one attribute test per drawn line and one connection count per tick.
"""
import base64
import json
import time
import zlib

import rospy
from std_msgs.msg import String

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

    def after_tick(self):
        """In the tick thread, the only one that changes the world: publish what this tick drew."""
        listening = self.publisher.get_num_connections() > 0
        if not listening:
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
        self.recording = True
        if not (message or self._ops or self.world.revision != self._revision):
            return
        self._revision = self.world.revision
        self._seq += 1
        message.update(seq=self._seq, stamp=time.time(), ops=self._ops,
                       turtles=[[t.name, t.x, t.y, t.theta, t.icon] for t in self.world.turtles()])
        self._ops = []
        self.publisher.publish(String(json.dumps(message)))
