"""Keyboard teleop with the TurtleBot3 layout (stand-in for ROBOTIS' turtlebot3_teleop)."""
