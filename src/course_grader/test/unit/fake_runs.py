"""Shared by the unit tests of the labs' checks: what a check asks of its Run beyond the simulator
and the node, which each test fakes its own way."""


class FakeRun:
    """Marks kept in the list `self.marks`, outcomes judged as they are, nothing to stop."""

    marks = None

    def mark(self, t, what, criterion):
        self.marks.append((t, what, criterion))

    def judged(self, outcomes):
        return outcomes

    def stop(self):
        pass
