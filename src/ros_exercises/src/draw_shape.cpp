// Exercise 5 (Figs. 8-10): the spawned turtle "robotics" drives a square or a triangle.
//   rosrun ros_exercises draw_shape _shape:=square _side:=3 _speed:=1 _turn_speed:=1
//   rosrun ros_exercises draw_shape _shape:=triangle _open_loop:=true
// Closed loop (the default): each side ends when the pose reaches the corner, and each turn ends
// when the pose's heading points at the next corner. The corners are worked out once from the start
// pose, so small errors do not add up and the figure closes on itself.
// Open loop (_open_loop:=true), as the report did with rostopic pub: drive for side/speed seconds,
// turn for (exterior angle)/turn_speed seconds; the figure then closes only roughly.
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>
#include <turtlesim/Pose.h>

#include "parameters.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

const double WORLD_SIZE = 11.088889;  // turtlesim's world is a square of this many metres
const double GAIN = 4.0;              // 1/s: slow down over the last speed/GAIN metres (or radians)
const double DISTANCE_TOLERANCE = 0.001;  // m
const double ANGLE_TOLERANCE = 0.001;     // rad

ros::Publisher pub;
turtlesim::Pose pose;
ros::Time pose_time;  // zero until the first pose arrives

void poseCallback(const turtlesim::Pose::ConstPtr& msg)
{
  pose = *msg;
  pose_time = ros::Time::now();
}

// False, with a message, when the poses have stopped coming (turtle killed, turtlesim closed):
// without them the closed loop would drive blind for ever.
bool poseIsFresh()
{
  if (ros::Time::now() - pose_time < ros::Duration(1.0))
    return true;
  ROS_ERROR("No pose of the turtle for 1 s: was it killed, or turtlesim closed?");
  return false;
}

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

void publishVelocity(double linear, double angular)
{
  geometry_msgs::Twist vel;
  vel.linear.x = linear;
  vel.angular.z = angular;
  pub.publish(vel);
}

// Turns on the spot until the heading is `heading`; false if the pose was lost.
bool turnTo(double heading, double turn_speed, ros::Rate& rate)
{
  while (ros::ok())
  {
    ros::spinOnce();
    if (!poseIsFresh())
      return false;
    double error = normalizeAngle(heading - pose.theta);
    if (std::fabs(error) < ANGLE_TOLERANCE)
      break;
    publishVelocity(0.0, std::copysign(approachSpeed(std::fabs(error), turn_speed), error));
    rate.sleep();
  }
  publishVelocity(0.0, 0.0);
  return true;
}

// Drives to the corner (x, y), steering towards it on the way; false if the pose was lost.
bool driveTo(double x, double y, double speed, ros::Rate& rate)
{
  while (ros::ok())
  {
    ros::spinOnce();
    if (!poseIsFresh())
      return false;
    double dx = x - pose.x, dy = y - pose.y;
    double ahead = dx * std::cos(pose.theta) + dy * std::sin(pose.theta);  // distance left along the heading
    if (ahead < DISTANCE_TOLERANCE)
      break;
    // Steering is left out on the last centimetre, where the direction to the corner is noise.
    double steer = ahead > 0.01 ? GAIN * normalizeAngle(std::atan2(dy, dx) - pose.theta) : 0.0;
    publishVelocity(approachSpeed(ahead, speed), steer);
    rate.sleep();
  }
  publishVelocity(0.0, 0.0);
  return true;
}

// Publishes the same velocity for `seconds`, then stops: the report's way.
void moveFor(double seconds, double linear, double angular, ros::Rate& rate)
{
  ros::Time end = ros::Time::now() + ros::Duration(seconds);
  while (ros::ok() && ros::Time::now() < end)
  {
    publishVelocity(linear, angular);
    rate.sleep();
  }
  publishVelocity(0.0, 0.0);
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "draw_shape");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");

  std::string shape = private_nh.param<std::string>("shape", "square");
  double side = 3.0, speed = 1.0, turn_speed = 1.0;
  bool numbers_read = readNumberParam(private_nh, "side", side) && readNumberParam(private_nh, "speed", speed) &&
                      readNumberParam(private_nh, "turn_speed", turn_speed);
  bool open_loop = false;
  if (private_nh.hasParam("open_loop") && !private_nh.getParam("open_loop", open_loop))
  {
    ROS_FATAL("~open_loop must be true or false");
    return 1;
  }
  int corners = shape == "square" ? 4 : shape == "triangle" ? 3 : 0;
  if (corners == 0)
  {
    ROS_FATAL("~shape must be square or triangle, got [%s]", shape.c_str());
    return 1;
  }
  if (!numbers_read || !(side > 0.0 && speed > 0.0 && turn_speed > 0.0))
  {
    ROS_FATAL("~side, ~speed and ~turn_speed must be positive numbers");
    return 1;
  }

  pub = nh.advertise<geometry_msgs::Twist>("robotics/cmd_vel", 1);
  ros::Subscriber sub = nh.subscribe("robotics/pose", 1, poseCallback);

  ROS_INFO("Waiting for the pose of the turtle on %s", sub.getTopic().c_str());
  ros::Time give_up = ros::Time::now() + ros::Duration(30.0);
  while (ros::ok() && pose_time.isZero() && ros::Time::now() < give_up)
  {
    ros::spinOnce();
    ros::Duration(0.01).sleep();
  }
  if (!ros::ok())
    return 0;
  if (pose_time.isZero())
  {
    ROS_FATAL("No pose on %s: is the turtle spawned? (rosrun ros_exercises spawn_turtle)", sub.getTopic().c_str());
    return 1;
  }

  // The corners, walking the figure counter-clockwise from the start pose; the last one is the start.
  const turtlesim::Pose start = pose;
  const double turn = 2.0 * M_PI / corners;  // exterior angle: 90 degrees for a square, 120 for a triangle
  std::vector<double> corner_x, corner_y;
  for (int i = 0; i < corners; ++i)
  {
    double previous_x = i == 0 ? start.x : corner_x.back(), previous_y = i == 0 ? start.y : corner_y.back();
    corner_x.push_back(previous_x + side * std::cos(start.theta + i * turn));
    corner_y.push_back(previous_y + side * std::sin(start.theta + i * turn));
    if (corner_x.back() < 0.0 || corner_x.back() > WORLD_SIZE || corner_y.back() < 0.0 || corner_y.back() > WORLD_SIZE)
    {
      ROS_FATAL("A %s with sides of %g m from (%f, %f) leaves turtlesim's world (0 to %f): corner (%f, %f)",
                shape.c_str(), side, start.x, start.y, WORLD_SIZE, corner_x.back(), corner_y.back());
      return 1;
    }
  }
  corner_x.back() = start.x;
  corner_y.back() = start.y;

  ROS_INFO("Drawing a %s with sides of %g m from (%f, %f), %s", shape.c_str(), side, start.x, start.y,
           open_loop ? "open loop (timed)" : "closed loop (from the pose)");
  ros::Rate rate(100);
  for (int i = 0; i < corners && ros::ok(); ++i)
  {
    if (open_loop)
    {
      moveFor(side / speed, speed, 0.0, rate);
      moveFor(turn / turn_speed, 0.0, turn_speed, rate);
    }
    else
    {
      if (!turnTo(std::atan2(corner_y[i] - pose.y, corner_x[i] - pose.x), turn_speed, rate) ||
          !driveTo(corner_x[i], corner_y[i], speed, rate))
        return 1;
      ROS_INFO("Corner %d at (%f, %f)", i + 1, pose.x, pose.y);
    }
  }
  if (!open_loop && !turnTo(start.theta, turn_speed, rate))
    return 1;

  ros::spinOnce();
  ROS_INFO("Finished the %s at (%f, %f, %f), %f m from the start", shape.c_str(), pose.x, pose.y, pose.theta,
           std::hypot(pose.x - start.x, pose.y - start.y));
  return 0;
}
