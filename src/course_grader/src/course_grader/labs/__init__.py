"""One module per lab: static_checks(session) (no ROS) and run_checks(session) (against the
simulators, on the session's master), each returning {criterion id: Outcome}."""
