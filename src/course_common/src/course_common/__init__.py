"""Helpers shared by the course's packages (no ROS imports here)."""
