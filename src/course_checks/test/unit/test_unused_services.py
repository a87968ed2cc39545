"""Calls of a simulator's services the lab does not use: which count, and the reason that names them."""
from course_checks import callers, turtle


CALLS = [('/clear', '/clear_node'), ('/turtle1/teleport_absolute', '/circle'), ('/reset', '/reset_node'),
         ('/turtlesim/save_canvas', '/tour')]


def test_the_turtle_labs_count_teleports_reset_and_save_canvas_not_clear():
    assert callers.unused(CALLS, turtle.UNUSED_SERVICES) == [
        ('/turtle1/teleport_absolute', '/circle'), ('/reset', '/reset_node'), ('/turtlesim/save_canvas', '/tour')]


def test_every_call_counts_where_the_lab_uses_no_service():
    assert callers.unused(CALLS) == CALLS


def test_the_criteria_fail_naming_the_node_and_the_service():
    verdicts = callers.called(['avoid_stops', 'avoid_stays'], [('/fake_tb3/save_picture', '/obstacle_avoidance')])
    assert sorted(verdicts) == ['avoid_stays', 'avoid_stops']
    for verdict in verdicts.values():
        assert not verdict.passed
        assert verdict.reason.startswith('not judged: /obstacle_avoidance called /fake_tb3/save_picture, which this '
                                         'lab does not use')
