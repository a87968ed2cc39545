#include <ros/ros.h>
#include <ros/ros.h>
#include *geonetry_msgs/Twist.h"

ros::Publisher pub;

void turtleCallback(const turtlesim::Pose::ConstPtr& msg)

{

geometry_msgs::Twist my_vel;

my_vel.ltnear.x = 1.6;

my_vel.angular.z = 2.1;

pub.publish(my_vel);

ROS_INFO("Turtle subscriber@(%f, %f, %f]",

msg->x, msg->y, msg->theta);
}

int main (int argc, char **argv)

{

ros::NodeHandle nh;

pub = nh.advertise<geonetry_msgs::Twist>("robotics/cmd_vel", 1);

ros::Subscriber sub = nh.subscribe("robotics/pose", 1,turtleCallback);

ros::Spin();

return 0;
}
