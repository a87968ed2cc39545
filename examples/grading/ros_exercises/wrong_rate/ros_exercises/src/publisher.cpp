// Exercise 0 (Fig. 1): send the digits of an ID number one by one, over and over, on the topic
// "ZabirovaKostyukova" at ~rate Hz (the report used 1 Hz and 50 Hz).
//   rosrun ros_exercises publisher _rate:=50 _id:=1234567
// The checks of ~id and ~rate, which the figure did not have, are in ros_exercises/parameters.h.
#include <ros/ros.h>
#include <std_msgs/Int32.h>

#include <ros_exercises/parameters.h>

#include <string>

int main(int argc, char **argv)
{
  ros::init(argc, argv, "publisher");
  ros::NodeHandle n;
  ros::NodeHandle private_nh("~");

  std::string id;
  double rate;
  if (!ros_exercises::readPublisherParams(private_nh, id, rate))
    return 1;

  ros::Publisher chatter_pub = n.advertise<std_msgs::Int32>("ZabirovaKostyukova", 1000);
  ros::Rate loop_rate(10);
  ROS_INFO("Publishing the digits of %s at %g Hz", id.c_str(), rate);

  std::size_t next = 0;
  while (ros::ok())
  {
    std_msgs::Int32 msg;
    msg.data = id[next] - '0';
    ROS_INFO("%d", msg.data);
    chatter_pub.publish(msg);
    next = (next + 1) % id.size();

    ros::spinOnce();
    loop_rate.sleep();
  }
  return 0;
}
