"""What a check says about one criterion: passed or not, the sentence that says why (what was
expected and what was seen, with numbers), and sentences about the usual mistakes (hints)."""


class Verdict:
    def __init__(self, passed, reason='', hints=()):
        self.passed = bool(passed)
        self.reason = reason
        self.hints = list(hints)

    def points(self, max_points):
        """The points of a criterion worth max_points: all or nothing."""
        return max_points if self.passed else 0

    def __repr__(self):
        return 'Verdict(%r, %r)' % (self.passed, self.reason)
