"""Helpers shared by the course's packages. Only teleop_ros imports rospy; simulator cores use the rest."""
