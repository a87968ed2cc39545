// Exercise 5 (Figs. 8-10): the spawned turtle "robotics" drives a square or a triangle: a side
// straight ahead (linear.x), then a turn on the spot (angular.z) through the exterior angle, 90
// degrees for a square and 120 for a triangle, and the same again at every corner.
//   rosrun ros_exercises draw_shape _shape:=square _side:=3 _speed:=1 _turn_speed:=1
//   rosrun ros_exercises draw_shape _shape:=triangle _open_loop:=true
// How a side and a turn end (timed with _open_loop:=true, as the report did with rostopic pub;
// from the pose by default, so that the figure closes) is in ros_exercises/shape_driver.h.
#include <ros/ros.h>

#include <ros_exercises/shape_driver.h>

int main(int argc, char **argv)
{
  ros::init(argc, argv, "draw_shape");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");

  ros_exercises::Shape shape;
  if (!ros_exercises::readShapeParams(private_nh, shape))
    return 1;

  // Velocities go to robotics/cmd_vel; the pose comes from robotics/pose.
  ros_exercises::ShapeDriver turtle(nh, "robotics", shape);
  if (!turtle.start())
    return ros::ok() ? 1 : 0;

  for (int corner = 0; corner < shape.corners && ros::ok(); ++corner)
  {
    if (!turtle.driveSide(corner) || !turtle.turnAtCorner(corner))
      return 1;
  }
  turtle.finish();
  return 0;
}
