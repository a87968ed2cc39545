"""Running the course's programs from outside and watching them: for tests, benchmarks and the tour.
Only the network scenarios import rospy."""
