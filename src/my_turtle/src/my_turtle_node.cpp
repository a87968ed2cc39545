// Stage 3 of the lab, slides "Gestire la teleoperazione" and "Guidare il robot": the final
// my_turtle_node. It drives the turtle with the keyboard teleop's commands and prints the pose.
// Run it with `roslaunch my_turtle move_turtle.launch` and, in a second terminal,
// `roslaunch turtlebot_teleop keyboard_teleop.launch` (or both at once: teleop_chain.launch).
//
// Differences from the slides: lin_vel_ and ang_vel_ are declared (the slides use them without a
// declaration), FORWARD_SPEED_MPS is gone (nothing drives forward on its own any more), and the
// start message says what the node now does instead of "Starting to move forward".
#include "ros/ros.h"
#include "geometry_msgs/Twist.h"
#include "turtlesim/Pose.h"

// The latest teleop command; the turtle stays still until the first one arrives.
double lin_vel_ = 0.0;
double ang_vel_ = 0.0;

// Topic messages callback
void poseCallback(const turtlesim::PoseConstPtr& msg)
{
    ROS_INFO("x: %.2f, y: %.2f", msg->x, msg->y);
}

// Teleop commands callback: keep the forward and turning speeds for the loop to send on
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

    // A publisher for the movement data
    ros::Publisher pub = node.advertise<geometry_msgs::Twist>("turtle1/cmd_vel", 10);

    // A listener for pose
    ros::Subscriber sub = node.subscribe("turtle1/pose", 10, poseCallback);

    // A listener for the keyboard teleop
    ros::Subscriber velocity_sub = node.subscribe("cmd_vel_mux/input/teleop", 1, velocityCallback);

    // Loop at 10Hz, publishing movement commands until we shut down
    ros::Rate rate(10);
    ROS_INFO("Waiting for teleop commands on cmd_vel_mux/input/teleop");
    while (ros::ok()) {
        geometry_msgs::Twist msg;
        msg.linear.x = lin_vel_;
        msg.angular.z = ang_vel_;
        pub.publish(msg);
        ros::spinOnce(); // Allow processing of incoming messages
        rate.sleep();
    }
}
