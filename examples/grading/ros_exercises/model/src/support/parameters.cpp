#include <ros_exercises/parameters.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

namespace ros_exercises
{
bool insideWorld(double x, double y)
{
  return x >= 0.0 && x <= WORLD_SIZE && y >= 0.0 && y <= WORLD_SIZE;
}

bool readNumberParam(const ros::NodeHandle& nh, const std::string& name, double& number)
{
  return !nh.hasParam(name) || (nh.getParam(name, number) && std::isfinite(number));
}

// The ID is normally a string; a number given on the command line arrives as an int
// (_id:=1234567), or as a double when it is too long for an int (_id:=12345678901): both are
// accepted. Returns "" when the parameter holds anything else.
static std::string readId(const ros::NodeHandle& private_nh)
{
  XmlRpc::XmlRpcValue value("1234567");
  private_nh.getParam("id", value);
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString)
    return static_cast<std::string>(value);
  if (value.getType() == XmlRpc::XmlRpcValue::TypeInt && static_cast<int>(value) >= 0)
    return std::to_string(static_cast<int>(value));
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble)
  {
    double number = value;
    if (number >= 0.0 && number < 1e15 && number == std::floor(number))  // doubles hold 15 digits exactly
      return std::to_string(static_cast<long long>(number));
  }
  return "";
}

bool readPublisherParams(const ros::NodeHandle& private_nh, std::string& id, double& rate)
{
  id = readId(private_nh);
  if (id.empty() || !std::all_of(id.begin(), id.end(), [](unsigned char c) { return std::isdigit(c); }))
  {
    ROS_FATAL("Parameter ~id must be a non-empty string of digits, e.g. _id:=1234567");
    return false;
  }
  rate = 1.0;
  if (!readNumberParam(private_nh, "rate", rate) || !(rate > 0.0))
  {
    ROS_FATAL("Parameter ~rate must be a positive number of Hz, e.g. _rate:=50");
    return false;
  }
  return true;
}

// Parses a whole argument as a finite number; false for "abc", "1x", "nan".
static bool parseNumber(const std::string& text, double& number)
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

bool readSpawnArguments(int argc, char** argv, const ros::NodeHandle& private_nh, turtlesim::Spawn::Request& spawn,
                        std::string& turtle_to_kill)
{
  double x = 1.0, y = 1.0, theta = 0.0;
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  if (args.size() == 4)
  {
    if (!parseNumber(args[1], x) || !parseNumber(args[2], y) || !parseNumber(args[3], theta))
    {
      ROS_ERROR("x, y and theta must be numbers, got [%s] [%s] [%s]", args[1].c_str(), args[2].c_str(),
                args[3].c_str());
      return false;
    }
  }
  else if (args.size() == 1)
  {
    if (!readNumberParam(private_nh, "x", x) || !readNumberParam(private_nh, "y", y) ||
        !readNumberParam(private_nh, "theta", theta))
    {
      ROS_ERROR("The parameters ~x, ~y and ~theta must be numbers");
      return false;
    }
  }
  else
  {
    ROS_ERROR("Usage: spawn_turtle [x y theta]   (or the parameters _x:= _y:= _theta:=)");
    return false;
  }
  if (!insideWorld(x, y))
  {
    ROS_ERROR("The position (%f, %f) is outside turtlesim's world: x and y go from 0 to %f", x, y, WORLD_SIZE);
    return false;
  }
  spawn.x = x;
  spawn.y = y;
  spawn.theta = theta;
  spawn.name = private_nh.param<std::string>("name", "robotics");
  turtle_to_kill = private_nh.param<std::string>("kill", "turtle1");
  if (turtle_to_kill == spawn.name)
  {
    ROS_ERROR("~kill names the turtle that is being spawned, [%s]", turtle_to_kill.c_str());
    return false;
  }
  return true;
}
}  // namespace ros_exercises
