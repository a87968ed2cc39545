"""Who called a simulator's services: each service once, with its first caller, in one line each."""
from course_common.service_calls import ServiceCalls, parse


def test_each_service_is_told_once_with_its_first_caller():
    calls = ServiceCalls()
    assert calls.text() == ''
    assert calls.note('/turtle1/teleport_absolute', '/circle')
    assert not calls.note('/turtle1/teleport_absolute', '/other')   # the text stays as it was
    assert calls.note('/reset', '/circle')
    assert parse(calls.text()) == [('/turtle1/teleport_absolute', '/circle'), ('/reset', '/circle')]


def test_a_caller_id_of_the_clients_choosing_stays_one_printable_word():
    calls = ServiceCalls()
    calls.note('/fake_tb3/save_picture', '/x\n/reset /course_grader')
    calls.note('/clear', '')
    assert calls.text() == '/fake_tb3/save_picture /x?/reset?/course_grader\n/clear ?'
    assert parse(calls.text()) == [('/fake_tb3/save_picture', '/x?/reset?/course_grader'), ('/clear', '?')]


def test_nothing_called_parses_to_no_call():
    assert parse('') == []
