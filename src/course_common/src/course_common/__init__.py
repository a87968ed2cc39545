"""What the course's nodes share at run time: the keyboard teleops' terminal (keyboard) and ROS side
(teleop_ros, the only module that imports rospy)."""
