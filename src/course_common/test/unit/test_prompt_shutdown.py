"""prompt_shutdown: rospy's shutdown wakes the node's registration thread instead of waiting for its
half-second poll to see the flag. In a process of its own (rospy's shutdown is for good)."""
import subprocess
import sys

SHUT_DOWN = r'''
import sys, threading, types
import rospy.core
from rospy.impl.registration import RegManager, get_registration_listeners
from course_common import prompt_shutdown

manager = RegManager(types.SimpleNamespace(done=False))
get_registration_listeners().add_listener(manager)
assert prompt_shutdown.registration_managers() == [manager]
# As RegManager.run waits for work (its own run needs a master): the last wait says whether it was
# woken (True) or timed out (False) before it saw the shutdown flag.
polled = types.SimpleNamespace(cond=threading.Condition())
woken = []
def registration_thread():
    while not rospy.core.is_shutdown():
        with polled.cond:
            woken.append(polled.cond.wait(0.5))
thread = threading.Thread(target=registration_thread)
rospy.core._add_shutdown_thread(thread)   # joined by signal_shutdown, as rospy's own
thread.start()
if sys.argv[1] == 'installed':
    prompt_shutdown.install([polled])
rospy.core.signal_shutdown('Ctrl-C')
print(woken[-1])
'''


def shut_down(how):
    return subprocess.run([sys.executable, '-c', SHUT_DOWN, how], stdout=subprocess.PIPE,
                          universal_newlines=True, timeout=30, check=True).stdout.strip()


def test_the_registration_thread_is_woken_once_the_shutdown_flag_is_set():
    assert shut_down('installed') == 'True'


def test_without_it_the_thread_ends_only_when_its_poll_times_out():
    assert shut_down('not installed') == 'False'
