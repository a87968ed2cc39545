"""What turtlesim shows of its canvas beyond the window: the ~save_canvas service, the ~canvas image
topic and the PNG written at shutdown. They only read pictures (a `snapshot()` callable returning
what the window shows, as an RGB array) and never change the world.
"""
import os

import rospkg
import rospy
from sensor_msgs.msg import Image
from std_srvs.srv import Trigger, TriggerResponse

from turtlesim import picture

CANVAS_TOPIC_PERIOD = 1.0  # seconds between ~canvas images (only while someone subscribes)


def canvas_path(param_value):
    """Where ~canvas_png points: relative paths start at ROS_HOME, where roslaunch runs nodes."""
    path = os.path.expanduser(str(param_value) if param_value else 'turtlesim_canvas.png')
    return os.path.normpath(os.path.join(rospkg.get_ros_home(), path))


def write_png(image, path):
    directory = os.path.dirname(path)
    if directory:
        os.makedirs(directory, exist_ok=True)
    picture.save_png(image, path)


class CanvasOutputs:
    """~save_canvas, ~canvas, and the canvas saved at shutdown when ~canvas_png was set at start.
    With `canvas_png` given (the command line's), it is where both write, and the parameter is not read."""

    def __init__(self, snapshot, canvas_png=None):
        self.snapshot = snapshot
        self.given_png = canvas_png
        self.png_at_shutdown = canvas_png if canvas_png is not None else rospy.get_param('~canvas_png', '')
        self._service = rospy.Service('~save_canvas', Trigger, self.save_canvas)
        self.canvas_pub = rospy.Publisher('~canvas', Image, queue_size=1,
                                          subscriber_listener=_PublishOnConnect(self))
        self._timer = rospy.Timer(rospy.Duration(CANVAS_TOPIC_PERIOD), self._publish_canvas)

    def save_canvas(self, _req):
        path = canvas_path(self.given_png if self.given_png is not None else rospy.get_param('~canvas_png', ''))
        try:
            write_png(self.snapshot(), path)
        except (OSError, ValueError) as error:
            message = 'Cannot save the canvas to %s: %s' % (path, error)
            rospy.logerr(message)
            return TriggerResponse(False, message)
        return TriggerResponse(True, path)

    def canvas_message(self):
        image = self.snapshot()
        message = Image()
        message.header.stamp = rospy.Time.now()
        message.header.frame_id = 'turtlesim_canvas'
        message.height, message.width = image.shape[:2]
        message.encoding = 'rgb8'
        message.step = message.width * 3
        message.data = image.tobytes()
        return message

    def _publish_canvas(self, _event):
        if self.canvas_pub.get_num_connections():
            self.canvas_pub.publish(self.canvas_message())

    def save_at_shutdown(self):
        if not self.png_at_shutdown:
            return
        path = canvas_path(self.png_at_shutdown)
        try:
            write_png(self.snapshot(), path)
        except (OSError, ValueError) as error:
            print('turtlesim: cannot save the canvas to %s: %s' % (path, error))
            return
        print('turtlesim: saved the canvas to %s' % path)


class _PublishOnConnect(rospy.SubscribeListener):
    """A new ~canvas subscriber gets a picture at once instead of waiting for the next period."""

    def __init__(self, outputs):
        super().__init__()
        self.outputs = outputs

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        peer_publish(self.outputs.canvas_message())
