#!/usr/bin/env python3
# Never run: the package does not build.
import rospy

rospy.init_node("trajectory")
rospy.spin()
