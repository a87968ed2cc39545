"""Periodic events on the simulated clock, in integer nanoseconds."""
import math


class Periodic:
    """Ticks at `rate` Hz of simulated time: tick k falls at round(k * 1e9 / rate) ns, so the
    long-run rate is exact whatever the rounding. The first tick is one period after 0."""

    def __init__(self, rate, name='rate'):
        try:
            rate = float(rate)
        except (TypeError, ValueError):
            raise ValueError('%s must be a number of Hz, got %r' % (name, rate)) from None
        if not (rate > 0 and math.isfinite(rate)):
            raise ValueError('%s must be a positive number of Hz, got %r' % (name, rate))
        self.rate = rate
        self.count = 1
        self.next_ns = self._at(1)

    def _at(self, count):
        return int(round(count * 1e9 / self.rate))

    def advance(self):
        self.count += 1
        self.next_ns = self._at(self.count)
