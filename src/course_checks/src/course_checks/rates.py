"""Rates of arrival and the digits a publisher cycles through (the lab report's exercise 1)."""
import collections
import math
import statistics

from course_checks.verdict import Verdict


def rate_of(entries):
    """Messages per second over (arrival time, message) entries (at least two): one over the slope
    of the least-squares line through the arrival times against the messages' order. Counted from
    first to last instead, a first or last time one clock step late moves the rate by a step in the
    whole span (each 4 ms step 0.1 Hz over 100 messages at 50 Hz); fitted, by about 6 / n of that
    over n messages (0.006 Hz). math.inf when the times do not advance (all the messages at one instant)."""
    times = [arrival - entries[0][0] for arrival, _ in entries]   # from the first: no digits lost to 1.7e9 s
    middle_index, mean_time = (len(times) - 1) / 2, sum(times) / len(times)
    spread = sum((index - middle_index) ** 2 for index in range(len(times)))
    covariance = sum((index - middle_index) * (arrival - mean_time) for index, arrival in enumerate(times))
    return spread / covariance if covariance > 0 else math.inf


def kept_rate(times):
    """The rate a publisher keeps: one over the median interval between arrival times (at least
    two). A node on simulated time that starts before the first /clock, or runs late on a busy
    machine, sends two or three at once while rospy.Rate catches up; those bursts move rate_of
    but not the median. 0.0 when the times do not advance."""
    intervals = [later - earlier for earlier, later in zip(times, times[1:])]
    median = statistics.median(intervals)
    return 1.0 / median if median > 0 else 0.0


class HeldClock:
    """A simulated clock for measuring a publisher's rate whatever the machine's load: it steps on
    `step_ns` at a time, but holds one expected period after the last message heard until the next
    one comes (a publisher on simulated time cannot publish before its period is over, and one kept
    from the processor finds the clock where it left it), or until its caller gives up waiting:
    then the publisher is slower than that period and the clock no longer holds. The messages'
    stamps are the clock's time when they came: never earlier than the publisher published them,
    and later by the time the clock ran on meanwhile. Until `settling` messages have come, and then
    on the step before each hold, the clock creeps (its caller waits a while after the step for a
    message sent at it), so that the messages are heard before it moves on from the step they were
    sent at, and stamped at it. Without it, messages sent while the clock ran freely before the
    first one came could keep the stamps periods late until they came at once, and a faster
    publisher's messages, heard as the clock reached each hold, were stamped one period apart.

    The clock holds only for messages heard a period or more after the first one: a publisher
    started before it had a time (a first /clock heard) sends its first message at time zero, and
    roscpp's and rospy's sleeps from time zero wait for the first time the publisher hears, then a
    whole period. Heard before it heard that time, such a message would put the hold before the
    publisher's next message, and the clock would wait for it until its caller gave up."""

    def __init__(self, period_ns, step_ns, settling=0, stand_still_after=None):
        self.period_ns = period_ns
        self.step_ns = step_ns
        self.settling = settling   # messages to hear before the clock creeps only before each hold
        self.stand_still_after = stand_still_after   # messages to hear before it stands still once
        self.stood_still = False
        self.heard_count = 0
        self.now_ns = 0
        self.hold_ns = None   # where the clock waits for the next message; None: it does not
        self.first_heard_ns = None   # the first message's stamp: the clock holds from a period after it
        self.gave_up = False

    def creeping(self):
        """Whether the caller should wait a while for a message after this step, before the next:
        until `settling` messages have come, and on the step before the hold."""
        before_hold = self.hold_ns is not None and self.now_ns + self.step_ns >= self.hold_ns
        return not self.gave_up and (not self.settled() or before_hold)

    def standing_still(self):
        """Whether the caller should now keep the clock where it is for a while (once, on the step
        before a hold, after `stand_still_after` messages): a publisher timed by the clock cannot
        send its next message before the clock reaches the hold, at most one already on its way; one
        timed by the wall clock goes on sending (publisher_verdict's `still`). A hold alone cannot
        tell them apart: it waits for a slower publisher's message as for one the machine delays."""
        due = (not self.stood_still and not self.gave_up and self.stand_still_after is not None
               and self.heard_count >= self.stand_still_after and self.hold_ns is not None
               and self.now_ns < self.hold_ns <= self.now_ns + self.step_ns)
        self.stood_still = self.stood_still or due
        return due

    def settled(self):
        """Whether `settling` messages have come (then the clock creeps only before each hold)."""
        return self.heard_count >= self.settling

    def holding(self):
        return self.hold_ns is not None and self.now_ns >= self.hold_ns

    def next_ns(self):
        """The clock's next time (the hold's exactly, when it comes first), or None while it holds."""
        if self.holding():
            return None
        self.now_ns += self.step_ns
        if self.hold_ns is not None:
            self.now_ns = min(self.now_ns, self.hold_ns)
        return self.now_ns

    def heard(self):
        """A message came: its stamp (seconds); the clock holds one period on (from a period after
        the first message)."""
        self.heard_count += 1
        if self.first_heard_ns is None:
            self.first_heard_ns = self.now_ns
        if not self.gave_up and self.now_ns >= self.first_heard_ns + self.period_ns:
            self.hold_ns = self.now_ns + self.period_ns
        return self.now_ns / 1e9

    def give_up(self):
        """No message came while the clock held (a slower publisher): it holds no more."""
        self.gave_up = True
        self.hold_ns = None


def creep_seconds(latencies, settled=True, heard_any=True, least=0.002):
    """How long a creeping HeldClock's caller waits after a step for a message sent at it (wall
    seconds): three times the longest of `latencies` (how long the last messages took from a step
    to their listener), at least `least`, at most 10 ms once the clock has settled and 100 ms
    before; the most while none is known. On a quiet machine a message takes 0.5 - 2 ms.
    Before it settles the clock must wait for the messages however long they take: one heard after
    the clock moved on is stamped late, and so is every message after it until one is heard
    before its hold (a stamp is never earlier than the hold). Left late when the measured messages
    begin and caught up among them, the stamps shorten the measurement by as much (80 ms of
    hearing while settling with 10 ms creeps, then messages heard at once: 50.7 Hz for 50).
    Settled, the clock only creeps on the step before each hold, where 10 ms is enough for a
    faster publisher's message to be stamped at its step. Before the first message (not
    `heard_any`), 10 ms: a publisher may sleep on the clock before it publishes (for its subscribers
    to connect, say), and at 100 ms a step one simulated second took 25 s of wall time, longer than
    the grader waits for a first message; the messages left out make up for a first one heard late."""
    most = 0.01 if settled or not heard_any else 0.1
    if not latencies:
        return most
    return min(most, max(least, 3 * max(latencies)))


# Messages heard while the clock stood still (HeldClock.standing_still) that show a publisher timed by
# the wall clock: one timed by the clock sends none, but one already on its way, and a grader that
# heard messages late may have one more queued.
WALL_TIMED_MESSAGES = 3


def publisher_verdict(entries, skipped, count, rate, tolerance, id_number, still=None, complete=True):
    """Exercise 1's publisher over the (stamp, digit) entries heard: the digits are the ID's in
    order, and the rate over entries[skipped:count] (rate_of: at least two) is `rate` Hz within
    `tolerance`. still: (seconds, [wall time of each message heard]) while the clock stood still:
    from WALL_TIMED_MESSAGES on, the publisher is timed by the wall clock, and its rate is taken
    from those wall times. complete: False when the grader stopped waiting before `count` messages
    came (and before its clock's window was over): fewer messages are not a rate."""
    in_order = cycles_through([digit for _, digit in entries], id_number)
    digits_wrong = '' if in_order.passed else '; ' + in_order.reason
    expected = 'expected the digits of %s, in order, at %g Hz ± %g; seen ' % (id_number, rate, tolerance)
    if still and len(still[1]) >= WALL_TIMED_MESSAGES:
        seconds, arrivals = still
        measured = rate_of([(arrival, None) for arrival in arrivals])
        return Verdict(abs(measured - rate) <= tolerance and in_order.passed, expected + (
            '%d messages in %g s while the simulated clock (/clock) stood still: the publisher is timed by the '
            'wall clock, not by ROS time (ros::Rate, rospy.Rate), so its rate was taken on the wall clock: '
            '%.2f Hz' % (len(arrivals), seconds, measured)) + digits_wrong)
    if not complete and len(entries) < count:
        return Verdict(False, expected + 'only %d of the %d messages it is measured over, before the run ended or the grader '
                       'stopped waiting' % (len(entries), count) + digits_wrong)
    measured_entries = entries[skipped:count]
    measured = rate_of(measured_entries)
    seen = ('%.2f Hz' % measured if math.isfinite(measured) else   # a loop without a sleep, say
            '%d messages at one instant' % len(measured_entries))
    return Verdict(abs(measured - rate) <= tolerance and in_order.passed, expected + seen + digits_wrong)


SHOWN_NUMBERS = 20   # of what a subscriber printed, the sentence shows this many


def subscriber_verdict(heard, sent):
    """Exercise 1's subscriber, run without the publisher while the grader published the digits
    `sent` on its topic, one at a time (none when nothing subscribed): `heard`, the numbers it
    printed (`I heard: [n]`, in order), must be those, and no other (a line the grader sent nothing
    for was not heard)."""
    heard, sent = list(heard), list(sent)
    if heard == sent:
        seen = 'each of them'
    elif not heard:
        seen = 'no such line'
    else:
        seen = ' '.join(str(number) for number in heard[:SHOWN_NUMBERS])
        seen += ' ...' if len(heard) > SHOWN_NUMBERS else ''
        extra = sum((collections.Counter(heard) - collections.Counter(sent)).values())
        seen += ' (%d line%s for %d digits%s)' % (len(heard), '' if len(heard) == 1 else 's', len(sent),
                                                   '; %d of them for no digit the grader published: printed, not '
                                                   'heard' % extra if extra else '')
    published = ' '.join(str(digit) for digit in sent) or 'none: nothing had subscribed when the lines came'
    return Verdict(heard == sent, 'expected `I heard: [d]` for each digit the grader published on ZabirovaKostyukova '
                   'in place of the publisher (%s), in order, and no other; seen %s' % (published, seen))


def cycles_through(digits, id_number):
    """Whether the digits are the ID's, in order, starting anywhere and wrapping round."""
    expected = [int(digit) for digit in id_number]
    starts = [start for start in range(len(expected))
              if all(digit == expected[(start + i) % len(expected)] for i, digit in enumerate(digits))]
    return Verdict(bool(starts), 'the digits of %s in order' % id_number if starts else
                   'digits %s are not the ID %s over and over' % (digits, id_number))
