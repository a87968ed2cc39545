"""Rates: how many key presses a page may send (pure)."""

KEYS_PER_SECOND = 40  # a held key repeats about 30 times a second
KEY_BURST = 40


class KeyBudget:
    """Token bucket: a page may press KEYS_PER_SECOND keys a second (bursts of KEY_BURST); presses
    beyond are ignored, so a runaway page cannot flood the simulator with commands."""

    def __init__(self, rate=KEYS_PER_SECOND, burst=KEY_BURST):
        self.rate, self.burst = float(rate), float(burst)
        self.tokens = float(burst)
        self.last = None
        self.refused = 0

    def allow(self, now):
        if self.last is not None:
            self.tokens = min(self.burst, self.tokens + (now - self.last) * self.rate)
        self.last = now
        if self.tokens >= 1.0:
            self.tokens -= 1.0
            return True
        self.refused += 1
        return False
