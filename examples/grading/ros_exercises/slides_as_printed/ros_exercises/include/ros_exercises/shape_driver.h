// How draw_shape drives a side and turns at a corner, and the checks of its parameters.
// Closed loop (the default): each side ends when the pose reaches the corner, and each turn ends
// when the pose's heading points at the next corner. The corners are worked out once from the start
// pose, so small errors do not add up and the figure closes on itself.
// Open loop (~open_loop true), as the report did with rostopic pub: drive for side/speed seconds,
// turn for (exterior angle)/turn_speed seconds; the figure then closes only roughly.
#ifndef ROS_EXERCISES_SHAPE_DRIVER_H
#define ROS_EXERCISES_SHAPE_DRIVER_H

#include <ros/ros.h>
#include <turtlesim/Pose.h>

#include <string>
#include <vector>

namespace ros_exercises
{
struct Shape
{
  std::string name = "square";  // ~shape: square or triangle
  int corners = 4;
  double side = 3.0;        // ~side, m
  double speed = 1.0;       // ~speed, m/s
  double turn_speed = 1.0;  // ~turn_speed, rad/s
  bool open_loop = false;   // ~open_loop
};

// Reads ~shape, ~side, ~speed, ~turn_speed and ~open_loop; false, with a message, when one is wrong.
bool readShapeParams(const ros::NodeHandle& private_nh, Shape& shape);

// Drives the turtle `turtle` on <turtle>/cmd_vel, watching its pose on <turtle>/pose.
class ShapeDriver
{
public:
  ShapeDriver(ros::NodeHandle& nh, const std::string& turtle, const Shape& shape);

  // Waits up to 30 s for the first pose, then works out the corners from it. False, with a message,
  // when no pose came or the shape leaves turtlesim's world.
  bool start();
  // Drives the side that ends at corner `corner` (0 is the first); false if the pose was lost.
  bool driveSide(int corner);
  // Turns on the spot towards the next side (after the last side: back to the start heading).
  bool turnAtCorner(int corner);
  // Logs where the turtle ended.
  void finish();

private:
  void poseCallback(const turtlesim::Pose::ConstPtr& msg);
  bool poseIsFresh();
  void publishVelocity(double linear, double angular);
  bool turnTo(double heading);
  bool driveTo(double x, double y);
  void moveFor(double seconds, double linear, double angular);

  Shape shape_;
  ros::Publisher pub_;
  ros::Subscriber sub_;
  turtlesim::Pose pose_;
  ros::Time pose_time_;  // zero until the first pose arrives
  turtlesim::Pose start_;
  std::vector<double> corner_x_, corner_y_;
  ros::Rate rate_;
};
}  // namespace ros_exercises

#endif  // ROS_EXERCISES_SHAPE_DRIVER_H
