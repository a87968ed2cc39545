// Exercise 2 (Fig. 4): the "turtle listener" prints the position and orientation of turtle1.
//   rosrun turtlesim turtlesim_node   and   rosrun ros_exercises turtle_listener
#include <ros/ros.h>
#include <turtlesim/Pose.h>

void poseCallback(const turtlesim::Pose::ConstPtr& msg)
{
  ROS_INFO("x: %f, y: %f, theta: %f", msg->x, msg->y, msg->theta);
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "turtle_listener");
  ros::NodeHandle n;

  ros::Subscriber sub = n.subscribe("turtle1/pose", 1000, poseCallback);
  ros::spin();
  return 0;
}
