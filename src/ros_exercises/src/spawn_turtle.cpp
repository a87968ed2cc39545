// Exercise 4 (Fig. 7): a client of turtlesim's services. It cleans the background with /clear,
// creates the turtle "robotics" with /spawn and removes turtle1 with /kill.
//   rosrun ros_exercises spawn_turtle                  spawn at x=1, y=1, theta=0
//   rosrun ros_exercises spawn_turtle 2 3 1.57         spawn at x=2, y=3, theta=1.57
//   rosrun ros_exercises spawn_turtle _x:=2 _y:=3 _theta:=1.57 _name:=robotics _kill:=turtle1
// _kill:="" kills nothing. Exits with 1 when a service fails, 2 on bad arguments.
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <turtlesim/Kill.h>
#include <turtlesim/Spawn.h>

#include "parameters.h"

#include <cmath>
#include <string>
#include <vector>

const double WORLD_SIZE = 11.088889;  // turtlesim's world is a square of this many metres

// Parses a whole argument as a finite number; false for "abc", "1x", "nan".
bool parseNumber(const std::string& text, double& number)
{
  try
  {
    std::size_t used = 0;
    number = std::stod(text, &used);
    return used == text.size() && std::isfinite(number);
  }
  catch (const std::exception&)
  {
    return false;
  }
}

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

int main(int argc, char **argv)
{
  ros::init(argc, argv, "spawn_turtle");
  ros::NodeHandle private_nh("~");

  double x = 1.0, y = 1.0, theta = 0.0;
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  if (args.size() == 4)
  {
    if (!parseNumber(args[1], x) || !parseNumber(args[2], y) || !parseNumber(args[3], theta))
    {
      ROS_ERROR("x, y and theta must be numbers, got [%s] [%s] [%s]", args[1].c_str(), args[2].c_str(),
                args[3].c_str());
      return 2;
    }
  }
  else if (args.size() == 1)
  {
    if (!readNumberParam(private_nh, "x", x) || !readNumberParam(private_nh, "y", y) ||
        !readNumberParam(private_nh, "theta", theta))
    {
      ROS_ERROR("The parameters ~x, ~y and ~theta must be numbers");
      return 2;
    }
  }
  else
  {
    ROS_ERROR("Usage: spawn_turtle [x y theta]   (or the parameters _x:= _y:= _theta:=)");
    return 2;
  }
  if (x < 0.0 || x > WORLD_SIZE || y < 0.0 || y > WORLD_SIZE)
  {
    ROS_ERROR("The position (%f, %f) is outside turtlesim's world: x and y go from 0 to %f", x, y, WORLD_SIZE);
    return 2;
  }
  turtlesim::Spawn spawn;
  spawn.request.x = x;
  spawn.request.y = y;
  spawn.request.theta = theta;
  spawn.request.name = private_nh.param<std::string>("name", "robotics");
  const std::string turtle_to_kill = private_nh.param<std::string>("kill", "turtle1");
  if (turtle_to_kill == spawn.request.name)
  {
    ROS_ERROR("~kill names the turtle that is being spawned, [%s]", turtle_to_kill.c_str());
    return 2;
  }

  // Clear before spawning: a node that waits for the new turtle to drive it (exercise 5) must not
  // see its first lines wiped. Spawn before killing: when the name is taken, nothing is killed.
  std_srvs::Empty clear;
  if (!callService("clear", clear))
  {
    ROS_ERROR("Could not clear the background");
    return 1;
  }

  if (!callService("spawn", spawn))
  {
    ROS_ERROR("Could not spawn the turtle [%s]: the name is taken or is not a valid ROS name",
              spawn.request.name.c_str());
    return 1;
  }
  ROS_INFO("Spawned the turtle [%s] at x=%f, y=%f, theta=%f", spawn.response.name.c_str(), spawn.request.x,
           spawn.request.y, spawn.request.theta);

  if (!turtle_to_kill.empty())
  {
    turtlesim::Kill kill;
    kill.request.name = turtle_to_kill;
    if (!callService("kill", kill))
    {
      ROS_ERROR("Could not kill the turtle [%s]: is there a turtle with that name?", turtle_to_kill.c_str());
      return 1;
    }
    ROS_INFO("Killed the turtle [%s]", turtle_to_kill.c_str());
  }
  return 0;
}
