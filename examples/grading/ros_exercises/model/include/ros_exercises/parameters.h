// The checks of the nodes' parameters and arguments, which the report's figures did not have: a
// typo (_rate:=fast, _side:=abc, a turtle outside the world) gets a clear message instead of a
// silent default.
#ifndef ROS_EXERCISES_PARAMETERS_H
#define ROS_EXERCISES_PARAMETERS_H

#include <ros/ros.h>
#include <turtlesim/Spawn.h>

#include <string>

namespace ros_exercises
{
const double WORLD_SIZE = 11.088889;  // turtlesim's world is a square of this many metres

// True when (x, y) is in turtlesim's world.
bool insideWorld(double x, double y);

// Leaves `number` alone when the parameter is not set; false when it is set but not a finite number.
// (NodeHandle::param() silently falls back to the default when a parameter holds text.)
bool readNumberParam(const ros::NodeHandle& nh, const std::string& name, double& number);

// publisher: ~id (digits; default 1234567) and ~rate (Hz; default 1). False, with a message, when
// either is wrong.
bool readPublisherParams(const ros::NodeHandle& private_nh, std::string& id, double& rate);

// spawn_turtle: where to spawn (the arguments "x y theta", else ~x ~y ~theta; default 1 1 0), the
// new turtle's name (~name, default robotics) and the turtle to kill (~kill, default turtle1; "" for
// none). False, with a message, when any of them is wrong.
bool readSpawnArguments(int argc, char** argv, const ros::NodeHandle& private_nh, turtlesim::Spawn::Request& spawn,
                        std::string& turtle_to_kill);

// Calls a turtlesim service, waiting a little for turtlesim to come up first.
template <class Service>
bool callService(const std::string& name, Service& srv)
{
  if (!ros::service::waitForService(name, ros::Duration(10.0)))
  {
    ROS_ERROR("The service %s is not available: is turtlesim running?", ros::names::resolve(name).c_str());
    return false;
  }
  return ros::service::call(name, srv);
}
}  // namespace ros_exercises

#endif  // ROS_EXERCISES_PARAMETERS_H
