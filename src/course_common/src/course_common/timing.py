"""Periodic events on the simulated clock, in integer nanoseconds, and the pace of simulated time
against the wall clock."""
import math

# Wall seconds behind its pace after which a simulation stops trying to catch up.
MAX_LAG = 0.25


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


class Pacer:
    """Paces simulated time against a wall clock (seconds, e.g. time.monotonic()): simulated time
    runs real_time_factor times as fast. A caller that falls more than max_lag wall seconds behind
    the pace carries on from where it is rather than rush to catch up (simulated time then runs
    slower than asked while the machine cannot keep up)."""

    def __init__(self, real_time_factor, start_wall, max_lag=MAX_LAG):
        if not (real_time_factor > 0 and math.isfinite(real_time_factor)):
            raise ValueError('real_time_factor must be a positive number, got %r'
                             % (real_time_factor,))
        self.real_time_factor = real_time_factor
        self.max_lag = max_lag
        self._anchor_wall, self._anchor_ns = start_wall, 0

    def due(self, sim_ns):
        """The wall time at which simulated time sim_ns falls due."""
        return self._anchor_wall + (sim_ns - self._anchor_ns) / 1e9 / self.real_time_factor

    def reached(self, sim_ns, now):
        """The caller runs simulated time sim_ns at wall time now: if that is more than max_lag
        late, the pace starts again from here."""
        if now - self.due(sim_ns) > self.max_lag:
            self._anchor_wall, self._anchor_ns = now, sim_ns

    def hold(self, sim_ns, now):
        """Simulated time stood at sim_ns until wall time now: if that is later than its pace,
        time goes on from there at the factor, without catching up the time it stood."""
        if now > self.due(sim_ns):
            self._anchor_wall, self._anchor_ns = now, sim_ns
