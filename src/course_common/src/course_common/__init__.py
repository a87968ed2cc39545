"""Helpers shared by the course's packages (no rospy here: simulator cores and tests use them)."""
