// Exercise 0 (Fig. 1): send the digits of an ID number one by one, over and over, on the topic
// "ZabirovaKostyukova" at ~rate Hz (the report used 1 Hz and 50 Hz).
//   rosrun ros_exercises publisher _rate:=50 _id:=1234567
#include <ros/ros.h>
#include <std_msgs/Int32.h>

#include "parameters.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

// The ID is normally a string; a number given on the command line arrives as an int
// (_id:=1234567), or as a double when it is too long for an int (_id:=12345678901): both are
// accepted. Returns "" when the parameter holds anything else.
std::string readId(const ros::NodeHandle& private_nh)
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

int main(int argc, char **argv)
{
  ros::init(argc, argv, "publisher");
  ros::NodeHandle n;
  ros::NodeHandle private_nh("~");

  const std::string id = readId(private_nh);
  if (id.empty() || !std::all_of(id.begin(), id.end(), [](unsigned char c) { return std::isdigit(c); }))
  {
    ROS_FATAL("Parameter ~id must be a non-empty string of digits, e.g. _id:=1234567");
    return 1;
  }
  double rate = 1.0;
  if (!readNumberParam(private_nh, "rate", rate) || !(rate > 0.0))
  {
    ROS_FATAL("Parameter ~rate must be a positive number of Hz, e.g. _rate:=50");
    return 1;
  }

  ros::Publisher chatter_pub = n.advertise<std_msgs::Int32>("ZabirovaKostyukova", 1000);
  ros::Rate loop_rate(rate);
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
