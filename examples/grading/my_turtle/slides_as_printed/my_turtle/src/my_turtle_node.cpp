#include "ros/ros.h"
#include "geometry_msgs/Twist.h"
#include "turtlesim/Pose.h"

// Topic messages callback
void poseCallback(const turtlesim::PoseConstPtr& msg)
{
    ROS_INFO("x: %.2f, y: %.2f", msg->x, msg->y);
}

void velocityCallback(const geometry_msgs::Twist::ConstPtr& vel)
{
    lin_vel_ = vel->linear.x;
    ang_vel_ = vel->angular.z;
}

int main(int argc, char **argv)
{
    // Initialize the node
    ros::init(argc, argv, "move_turtle");
    ros::NodeHandle node;

    ros::Publisher pub = node.advertise<geometry_msgs::Twist>("turtle1/cmd_vel", 10);

    // A listener for pose
    ros::Subscriber sub = node.subscribe("turtle1/pose", 10, poseCallback);

    ros::Subscriber velocity_sub = node.subscribe("cmd_vel_mux/input/teleop", 1, velocityCallback);

    // Loop at 10Hz, publishing movement commands until we shut down
    ros::Rate rate(10);
    ROS_INFO("Starting to move forward");
    while (ros::ok()) {
        geometry_msgs::Twist msg;
        msg.linear.x = lin_vel_;
        msg.angular.z = ang_vel_;
        pub.publish(msg);
        ros::spinOnce(); // Allow processing of incoming messages
        rate.sleep();
    }
}
