"""For the rostests: rates of header stamps, rosout lines and TF lookups."""
import rospy
import tf2_ros


def stamp_rate(recorder, start_stamp, end_stamp):
    """Messages per second of header stamps: those of a TopicRecorder stamped in [start, end), over end - start."""
    count = sum(1 for message in recorder.messages() if start_stamp <= message.header.stamp < end_stamp)
    return count / (end_stamp - start_stamp).to_sec()


def rosout_lines(recorder, text):
    """The texts of the /rosout messages (a TopicRecorder of rosgraph_msgs/Log) that contain `text`."""
    return [message.msg for message in recorder.messages() if text in message.msg]


def lookup(tf_buffer, parent, child):
    """The latest transform parent -> child (geometry_msgs/Transform), or None while unknown."""
    try:
        return tf_buffer.lookup_transform(parent, child, rospy.Time(0)).transform
    except (tf2_ros.LookupException, tf2_ros.ExtrapolationException, tf2_ros.ConnectivityException):
        return None
