"""What a check says about one criterion: passed or not, the sentence that says why (what was
expected and what was seen, with numbers), and sentences about the usual mistakes (hints)."""


def decimal(value, places):
    """`value` written with `places` decimals, never as '-0.00' (a fit's centre at 0 may come out as
    -1e-17, and which sign depends on the numpy of the machine)."""
    text = '%.*f' % (places, value)
    return text[1:] if text.lstrip('-0.') == '' and text.startswith('-') else text


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
