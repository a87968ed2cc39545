#include <ros_exercises/parameters.h>
#include <ros_exercises/shape_driver.h>

#include <geometry_msgs/Twist.h>

#include <algorithm>
#include <cmath>

namespace ros_exercises
{
namespace
{
const double GAIN = 4.0;                  // 1/s: slow down over the last speed/GAIN metres (or radians)
const double DISTANCE_TOLERANCE = 0.001;  // m
const double ANGLE_TOLERANCE = 0.001;     // rad

// Wraps an angle into [-pi, pi).
double normalizeAngle(double angle)
{
  return angle - 2.0 * M_PI * std::floor((angle + M_PI) / (2.0 * M_PI));
}

// Proportional speed with a floor, so the turtle neither overshoots nor creeps for ever.
double approachSpeed(double remaining, double max_speed)
{
  return std::min(max_speed, std::max(GAIN * remaining, 0.05 * max_speed));
}
}  // namespace

bool readShapeParams(const ros::NodeHandle& private_nh, Shape& shape)
{
  shape.name = private_nh.param<std::string>("shape", "square");
  bool numbers_read = readNumberParam(private_nh, "side", shape.side) &&
                      readNumberParam(private_nh, "speed", shape.speed) &&
                      readNumberParam(private_nh, "turn_speed", shape.turn_speed);
  if (private_nh.hasParam("open_loop") && !private_nh.getParam("open_loop", shape.open_loop))
  {
    ROS_FATAL("~open_loop must be true or false");
    return false;
  }
  shape.corners = shape.name == "square" ? 4 : shape.name == "triangle" ? 3 : 0;
  if (shape.corners == 0)
  {
    ROS_FATAL("~shape must be square or triangle, got [%s]", shape.name.c_str());
    return false;
  }
  if (!numbers_read || !(shape.side > 0.0 && shape.speed > 0.0 && shape.turn_speed > 0.0))
  {
    ROS_FATAL("~side, ~speed and ~turn_speed must be positive numbers");
    return false;
  }
  return true;
}

ShapeDriver::ShapeDriver(ros::NodeHandle& nh, const std::string& turtle, const Shape& shape)
  : shape_(shape), rate_(100)
{
  pub_ = nh.advertise<geometry_msgs::Twist>(turtle + "/cmd_vel", 1);
  sub_ = nh.subscribe(turtle + "/pose", 1, &ShapeDriver::poseCallback, this);
}

void ShapeDriver::poseCallback(const turtlesim::Pose::ConstPtr& msg)
{
  pose_ = *msg;
  pose_time_ = ros::Time::now();
}

// False, with a message, when the poses have stopped coming (turtle killed, turtlesim closed):
// without them the closed loop would drive blind for ever.
bool ShapeDriver::poseIsFresh()
{
  if (ros::Time::now() - pose_time_ < ros::Duration(1.0))
    return true;
  ROS_ERROR("No pose of the turtle for 1 s: was it killed, or turtlesim closed?");
  return false;
}

void ShapeDriver::publishVelocity(double linear, double angular)
{
  geometry_msgs::Twist vel;
  vel.linear.x = linear;
  vel.angular.z = angular;
  pub_.publish(vel);
}

bool ShapeDriver::start()
{
  ROS_INFO("Waiting for the pose of the turtle on %s", sub_.getTopic().c_str());
  ros::Time give_up = ros::Time::now() + ros::Duration(30.0);
  while (ros::ok() && pose_time_.isZero() && ros::Time::now() < give_up)
  {
    ros::spinOnce();
    ros::Duration(0.01).sleep();
  }
  if (!ros::ok())
    return false;
  if (pose_time_.isZero())
  {
    ROS_FATAL("No pose on %s: is the turtle spawned? (rosrun ros_exercises spawn_turtle)", sub_.getTopic().c_str());
    return false;
  }

  // The corners, walking the figure counter-clockwise from the start pose; the last one is the start.
  start_ = pose_;
  const double turn = 2.0 * M_PI / shape_.corners;
  for (int i = 0; i < shape_.corners; ++i)
  {
    double previous_x = i == 0 ? start_.x : corner_x_.back(), previous_y = i == 0 ? start_.y : corner_y_.back();
    corner_x_.push_back(previous_x + shape_.side * std::cos(start_.theta + i * turn));
    corner_y_.push_back(previous_y + shape_.side * std::sin(start_.theta + i * turn));
    if (!insideWorld(corner_x_.back(), corner_y_.back()))
    {
      ROS_FATAL("A %s with sides of %g m from (%f, %f) leaves turtlesim's world (0 to %f): corner (%f, %f)",
                shape_.name.c_str(), shape_.side, start_.x, start_.y, WORLD_SIZE, corner_x_.back(), corner_y_.back());
      return false;
    }
  }
  corner_x_.back() = start_.x;
  corner_y_.back() = start_.y;

  ROS_INFO("Drawing a %s with sides of %g m from (%f, %f), %s", shape_.name.c_str(), shape_.side, start_.x,
           start_.y, shape_.open_loop ? "open loop (timed)" : "closed loop (from the pose)");
  return true;
}

bool ShapeDriver::driveSide(int corner)
{
  if (shape_.open_loop)
  {
    moveFor(shape_.side / shape_.speed, shape_.speed, 0.0);
    return true;
  }
  if (!driveTo(corner_x_[corner], corner_y_[corner]))
    return false;
  ROS_INFO("Corner %d at (%f, %f)", corner + 1, pose_.x, pose_.y);
  return true;
}

bool ShapeDriver::turnAtCorner(int corner)
{
  if (shape_.open_loop)
  {
    const double turn = 2.0 * M_PI / shape_.corners;  // exterior angle: 90 degrees for a square, 120 for a triangle
    moveFor(turn / shape_.turn_speed, 0.0, shape_.turn_speed);
    return true;
  }
  if (corner + 1 == shape_.corners)
    return turnTo(start_.theta);
  return turnTo(std::atan2(corner_y_[corner + 1] - pose_.y, corner_x_[corner + 1] - pose_.x));
}

void ShapeDriver::finish()
{
  ros::spinOnce();
  ROS_INFO("Finished the %s at (%f, %f, %f), %f m from the start", shape_.name.c_str(), pose_.x, pose_.y,
           pose_.theta, std::hypot(pose_.x - start_.x, pose_.y - start_.y));
}

// Turns on the spot until the heading is `heading`; false if the pose was lost.
bool ShapeDriver::turnTo(double heading)
{
  while (ros::ok())
  {
    ros::spinOnce();
    if (!poseIsFresh())
      return false;
    double error = normalizeAngle(heading - pose_.theta);
    if (std::fabs(error) < ANGLE_TOLERANCE)
      break;
    publishVelocity(0.0, std::copysign(approachSpeed(std::fabs(error), shape_.turn_speed), error));
    rate_.sleep();
  }
  publishVelocity(0.0, 0.0);
  return true;
}

// Drives to the corner (x, y), steering towards it on the way; false if the pose was lost.
bool ShapeDriver::driveTo(double x, double y)
{
  while (ros::ok())
  {
    ros::spinOnce();
    if (!poseIsFresh())
      return false;
    double dx = x - pose_.x, dy = y - pose_.y;
    double ahead = dx * std::cos(pose_.theta) + dy * std::sin(pose_.theta);  // distance left along the heading
    if (ahead < DISTANCE_TOLERANCE)
      break;
    // Steering is left out on the last centimetre, where the direction to the corner is noise.
    double steer = ahead > 0.01 ? GAIN * normalizeAngle(std::atan2(dy, dx) - pose_.theta) : 0.0;
    publishVelocity(approachSpeed(ahead, shape_.speed), steer);
    rate_.sleep();
  }
  publishVelocity(0.0, 0.0);
  return true;
}

// Publishes the same velocity for `seconds`, then stops: the report's way.
void ShapeDriver::moveFor(double seconds, double linear, double angular)
{
  ros::Time end = ros::Time::now() + ros::Duration(seconds);
  while (ros::ok() && ros::Time::now() < end)
  {
    publishVelocity(linear, angular);
    rate_.sleep();
  }
  publishVelocity(0.0, 0.0);
}
}  // namespace ros_exercises
