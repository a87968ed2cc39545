"""fake_tb3: a 2D TurtleBot3 simulator standing in for Gazebo.

The pure core (models, kinematics, geometry, world, lidar, simulation, render, timing, drive, urdf)
imports no rospy; `node` and `drive_node` are the thin ROS layers around it.
"""
