"""draw_square: reset turtlesim, then drive turtle1 around 2 m squares, as the original demo does.

A timer at turtlesim's tick (turtlesim.world.TICK_SECONDS, as in the original) runs a four-state
machine on turtle1's pose: forward at 1 m/s until 2 m ahead, stop, turn at 0.4 rad/s by a quarter
turn, stop, and again. Logs each new goal.
"""
import math

import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

from turtlesim.msg import Pose
from turtlesim.world import TICK_SECONDS

PI = 3.141592  # the demo's own constant
SIDE = 2.0  # metres
FORWARD_SPEED = 1.0  # m/s
TURN_SPEED = 0.4  # rad/s
POSITION_TOLERANCE = 0.1
ANGLE_TOLERANCE = 0.01
STOPPED_BELOW = 0.0001  # both pose velocities under this: the turtle has stopped
FORWARD, STOP_FORWARD, TURN, STOP_TURN = range(4)


class SquareDriver:
    def __init__(self):
        self.pose = None
        self.goal = None  # (x, y, theta)
        self.state = FORWARD
        self.cmd_vel = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)

    def on_pose(self, pose):
        self.pose = pose

    def command(self, linear, angular):
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        self.cmd_vel.publish(twist)

    def set_goal(self, x, y, theta):
        self.goal = (x, y, theta)
        rospy.loginfo('New goal [%f %f, %f]' % self.goal)

    def goal_ahead(self):
        pose = self.pose
        self.set_goal(pose.x + SIDE * math.cos(pose.theta), pose.y + SIDE * math.sin(pose.theta), pose.theta)

    def goal_turned(self):
        theta = math.fmod(self.pose.theta + PI / 2.0, 2.0 * PI)
        if theta >= PI:
            theta -= 2.0 * PI
        self.set_goal(self.pose.x, self.pose.y, theta)

    def reached_goal(self):
        x, y, theta = self.goal
        return (abs(self.pose.x - x) < POSITION_TOLERANCE and abs(self.pose.y - y) < POSITION_TOLERANCE
                and abs(self.pose.theta - theta) < ANGLE_TOLERANCE)

    def stopped(self):
        return self.pose.linear_velocity < STOPPED_BELOW and self.pose.angular_velocity < STOPPED_BELOW

    def step(self, _event):
        if self.pose is None:
            return
        if self.goal is None:
            self.goal_ahead()
        if self.state in (FORWARD, TURN):
            if self.reached_goal():
                self.state = STOP_FORWARD if self.state == FORWARD else STOP_TURN
                self.command(0.0, 0.0)
            elif self.state == FORWARD:
                self.command(FORWARD_SPEED, 0.0)
            else:
                self.command(0.0, TURN_SPEED)
        elif not self.stopped():
            self.command(0.0, 0.0)
        else:
            rospy.loginfo('Reached goal')
            if self.state == STOP_FORWARD:
                self.state = TURN
                self.goal_turned()
            else:
                self.state = FORWARD
                self.goal_ahead()


def main():
    rospy.init_node('draw_square')
    rospy.wait_for_service('reset')
    rospy.ServiceProxy('reset', Empty)()
    driver = SquareDriver()
    # Subscribed after the reset has been applied, so no pose from before it sets the first goal.
    rospy.Subscriber('turtle1/pose', Pose, driver.on_pose, queue_size=1)
    rospy.Timer(rospy.Duration(TICK_SECONDS), driver.step)
    rospy.spin()
