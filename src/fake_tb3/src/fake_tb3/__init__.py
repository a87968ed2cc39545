"""fake_tb3: a 2D TurtleBot3 simulator standing in for Gazebo.

The pure core (models, kinematics, geometry, world, lidar, imu, simulation, render, timing,
turtlebot3_drive, urdf) imports no rospy; `node` and `turtlebot3_drive_node` are the thin ROS
layers around it.
"""
