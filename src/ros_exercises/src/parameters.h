// Strict reading of number parameters, shared by the nodes: NodeHandle::param() silently falls back
// to the default when a parameter holds text (_side:=abc), which would hide a typo.
#ifndef ROS_EXERCISES_PARAMETERS_H
#define ROS_EXERCISES_PARAMETERS_H

#include <ros/ros.h>

#include <cmath>
#include <string>

// Leaves `number` alone when the parameter is not set; false when it is set but not a finite number.
inline bool readNumberParam(const ros::NodeHandle& nh, const std::string& name, double& number)
{
  return !nh.hasParam(name) || (nh.getParam(name, number) && std::isfinite(number));
}

#endif  // ROS_EXERCISES_PARAMETERS_H
