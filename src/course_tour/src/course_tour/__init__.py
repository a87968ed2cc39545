"""The guided tour of the course: each lab run headless for a few seconds, with a summary."""
