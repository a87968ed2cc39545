// Exercise 0 (Fig. 2): print every digit that arrives on the topic "ZabirovaKostyukova".
//   rosrun ros_exercises subscriber
#include <ros/ros.h>
#include <std_msgs/Int32.h>

void chatterCallback(const std_msgs::Int32::ConstPtr& msg)
{
  ROS_INFO("I heard: [%d]", msg->data);
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "subscriber");
  ros::NodeHandle n;

  ros::Subscriber sub = n.subscribe("ZabirovaKostyukova", 1000, chatterCallback);
  ros::spin();
  return 0;
}
