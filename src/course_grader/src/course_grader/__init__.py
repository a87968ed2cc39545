"""Grading a class's submissions of a course lab against the course's simulators."""
