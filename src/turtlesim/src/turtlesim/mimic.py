"""mimic: make one turtle copy another's motion (node turtle_mimic).

Subscribes input/pose and publishes output/cmd_vel with the pose's velocities, so
`mimic input:=turtle1 output:=turtle2` makes turtle2 repeat what turtle1 does. The pose's linear
velocity is a speed (never negative): a turtle driving backwards is mimicked driving forwards.

`input` and `output` are namespaces, remapped as a whole (as a roscpp NodeHandle("input") is):
rospy applies a remapping to a name only, so the two namespaces are resolved first.
"""
import rospy
from geometry_msgs.msg import Twist

from turtlesim.msg import Pose


def main():
    rospy.init_node('turtle_mimic')
    cmd_vel = rospy.Publisher(rospy.resolve_name('output') + '/cmd_vel', Twist, queue_size=1)

    def copy_motion(pose):
        twist = Twist()
        twist.linear.x, twist.angular.z = pose.linear_velocity, pose.angular_velocity
        cmd_vel.publish(twist)

    rospy.Subscriber(rospy.resolve_name('input') + '/pose', Pose, copy_motion, queue_size=1)
    rospy.spin()
