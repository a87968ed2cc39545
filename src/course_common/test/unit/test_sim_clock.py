"""A simulator's own rospy time (sim_clock.set_own_time): what rospy then gives as the time, and a
rospy.sleep on simulated time in another thread of the node ending once the time has come."""
import threading

import genpy
import pytest
import rospy
import rospy.rostime

from course_common.sim_clock import set_own_time
from course_common.waiting import poll_until


@pytest.fixture
def simulated_time():
    rospy.rostime.set_rostime_initialized(True)
    yield
    rospy.rostime._rostime_current = None   # the wall clock again, for the tests after
    rospy.rostime.set_rostime_initialized(False)


def test_the_time_set_is_rospys_time(simulated_time):
    set_own_time(rospy.Time(3, 5))
    assert rospy.get_rostime() == rospy.Time(3, 5) and type(rospy.get_rostime()) is rospy.Time
    assert not rospy.rostime.is_wallclock()
    set_own_time(genpy.Time(4, 0))   # another Time type: made a rospy.Time, as rospy's own setter does
    assert rospy.get_rostime() == rospy.Time(4, 0) and type(rospy.get_rostime()) is rospy.Time


def test_a_sleep_on_simulated_time_ends_when_the_time_comes(simulated_time):
    set_own_time(rospy.Time(1, 0))
    slept = threading.Event()
    sleeper = threading.Thread(target=lambda: (rospy.sleep(0.5), slept.set()), daemon=True)
    sleeper.start()
    # Only once the sleeper waits on rospy's condition has it read its start (1.0 s): a time set
    # before would move its end.
    assert poll_until(lambda: rospy.rostime.get_rostime_cond()._waiters, 5.0, poll=0.001)
    set_own_time(rospy.Time(1, 200000000))
    assert not slept.wait(0.5)   # 0.2 simulated seconds of its 0.5: still asleep (the wall clock does not count)
    set_own_time(rospy.Time(1, 600000000))
    assert slept.wait(5.0)
