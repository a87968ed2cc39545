"""What the course's nodes and simulators share at run time: the keyboard teleops' terminal
(keyboard) and ROS side (teleop_ros), and the simulators' request queue (request_queue), simulated
time (timing) and batched publishing (batched_writes). Only teleop_ros imports rospy."""
