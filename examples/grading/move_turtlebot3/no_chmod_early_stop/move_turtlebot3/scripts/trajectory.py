import rospy
from geometry_msgs.msg import Twist

rospy.init_node('vel_publisher')
pub = rospy.Publisher('cmd_vel', Twist, queue_size=10)
move = Twist()
move.linear.x = 1
move.angular.z = 1
rate = rospy.Rate(1)
while not rospy.is_shutdown():
    pub.publish(move)
    rate.sleep()
