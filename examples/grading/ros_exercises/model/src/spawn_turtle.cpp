// Exercise 4 (Fig. 7): a client of turtlesim's services. It cleans the background with /clear,
// creates the turtle "robotics" with /spawn and removes turtle1 with /kill.
//   rosrun ros_exercises spawn_turtle                  spawn at x=1, y=1, theta=0
//   rosrun ros_exercises spawn_turtle 2 3 1.57         spawn at x=2, y=3, theta=1.57
//   rosrun ros_exercises spawn_turtle _x:=2 _y:=3 _theta:=1.57 _name:=robotics _kill:=turtle1
// _kill:="" kills nothing. Exits with 1 when a service fails, 2 on bad arguments (the checks, and
// the wait for turtlesim's services, are in ros_exercises/parameters.h).
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <turtlesim/Kill.h>
#include <turtlesim/Spawn.h>

#include <ros_exercises/parameters.h>

#include <string>

using ros_exercises::callService;

int main(int argc, char **argv)
{
  ros::init(argc, argv, "spawn_turtle");
  ros::NodeHandle private_nh("~");

  turtlesim::Spawn spawn;
  std::string turtle_to_kill;
  if (!ros_exercises::readSpawnArguments(argc, argv, private_nh, spawn.request, turtle_to_kill))
    return 2;

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
