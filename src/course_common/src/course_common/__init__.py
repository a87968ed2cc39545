"""What the course's nodes, simulators, the grader's trusted side and the tests share at run time: the
keyboard teleops' terminal (keyboard) and ROS side (teleop_ros); the simulators' request queue
(request_queue), simulated time (timing, sim_clock), batched publishing (batched_writes), record
(sim_record, sim_record_ros) and service calls (service_calls, service_calls_ros); recording a topic
(topic_recorder); processes, the process table and waiting (processes, process_table, waiting). The
modules named *_ros, sim_clock and topic_recorder import rospy; the others do not."""
