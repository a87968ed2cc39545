"""ROS layer of the wanderer (Turtlebot3Drive, the turtlebot3_drive behaviour): scan and odom in,
Twist out on the topic named by the global parameter cmd_vel_topic_name."""
import math
import threading

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from fake_tb3.turtlebot3_drive import Turtlebot3Drive, read_beams


class DriveNode:
    def __init__(self):
        self.drive = Turtlebot3Drive()
        self.beams = None
        self.lock = threading.Lock()  # the last command must be the stop at shutdown
        self.stopped = False
        self.warned_scan = False
        topic = rospy.get_param('cmd_vel_topic_name', 'cmd_vel')
        self.publisher = rospy.Publisher(topic, Twist, queue_size=10)
        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1)
        rospy.Subscriber('odom', Odometry, self.on_odom, queue_size=1)
        rospy.on_shutdown(self.stop)
        rospy.loginfo('%s: wandering, commands on %s', rospy.get_name(),
                      self.publisher.resolved_name)

    def on_scan(self, scan):
        beams = read_beams(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_max)
        if beams is None and not self.warned_scan:
            rospy.logwarn('%s: the scan (%d beams from %.3f rad by %.4f rad) lacks the front, left '
                          'or right beam: standing still', rospy.get_name(), len(scan.ranges),
                          scan.angle_min, scan.angle_increment)
        self.warned_scan = beams is None
        self.beams = beams

    def on_odom(self, odom):
        q = odom.pose.pose.orientation
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
        twist = Twist()
        twist.linear.x, twist.angular.z = self.drive.command(self.beams, yaw)
        with self.lock:
            if not self.stopped:
                self.publisher.publish(twist)

    def stop(self):
        """On shutdown: a zero Twist and nothing after it (the simulator keeps the last command)."""
        with self.lock:
            self.stopped = True
            self.publisher.publish(Twist())


def main():
    rospy.init_node('turtlebot3_drive')
    DriveNode()
    rospy.spin()
