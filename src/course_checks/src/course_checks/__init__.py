"""The checks a student's node is judged by, shared by the course's rostests and the grader."""
