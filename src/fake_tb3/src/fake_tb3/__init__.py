"""fake_tb3: a 2D TurtleBot3 simulator standing in for Gazebo.

The modules below `node` and `drive_node` import no rospy: they are the pure simulator core.
"""
