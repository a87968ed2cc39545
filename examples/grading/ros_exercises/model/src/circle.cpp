// Exercise 3 (Fig. 5): publish linear.x = angular.z = 1.0 so that the turtle drives a circle of
// radius 1 m, and print its pose. Fig. 5 drives the spawned turtle "robotics"; remap the topics for
// that (exercise3.launch turtle:=robotics does):
//   rosrun ros_exercises circle turtle1/cmd_vel:=robotics/cmd_vel turtle1/pose:=robotics/pose
// Compared with the figure: the missing includes (Pose.h), ros::init and "geometry_msgs" are put
// right, and ros::spin() is spelt with a small s.
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>
#include <turtlesim/Pose.h>

ros::Publisher pub;

// Every new pose is answered with the same velocity, so the turtle never stops (turtlesim stops a
// turtle that has had no command for 1 s).
void turtleCallback(const turtlesim::Pose::ConstPtr& msg)
{
  geometry_msgs::Twist my_vel;
  my_vel.linear.x = 1.0;
  my_vel.angular.z = 1.0;
  pub.publish(my_vel);

  ROS_INFO("Turtle subscriber@[%f, %f, %f]", msg->x, msg->y, msg->theta);
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "circle");
  ros::NodeHandle nh;

  pub = nh.advertise<geometry_msgs::Twist>("turtle1/cmd_vel", 1);
  ros::Subscriber sub = nh.subscribe("turtle1/pose", 1, turtleCallback);

  ros::spin();
  return 0;
}
