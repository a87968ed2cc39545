"""The closing count of ./test.sh: rostest failures count, wrappers do not double-count, skips fail."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COUNTER = os.path.join(ROOT, 'tools', 'count_results.py')


def write(folder, name, cases):
    body = ''.join('<testcase classname="t" name="%s">%s</testcase>' % (case, inner)
                   for case, inner in cases)
    with open(os.path.join(folder, name), 'w') as xml:
        xml.write('<?xml version="1.0"?><testsuite tests="%d">%s</testsuite>' % (len(cases), body))


def run_counter(folder, *extra):
    result = subprocess.run([sys.executable, COUNTER, str(folder)] + list(extra),
                            stdout=subprocess.PIPE, universal_newlines=True)
    return result.returncode, result.stdout.splitlines()[-1], result.stdout


def test_a_failing_case_inside_a_rostest_counts_as_failed(tmp_path):
    write(tmp_path, 'rosunit-square.xml', [('corners', '<failure message="12 cm off"/>'), ('closes', '')])
    write(tmp_path, 'rostest-test_square.xml', [('testsquare', '')])
    code, last, out = run_counter(tmp_path)
    assert (code, last) == (1, '1 passed, 1 failed')
    assert 'FAILED: t.corners\n    12 cm off\n' in out


def test_a_failures_last_lines_are_printed_under_its_name(tmp_path):
    traceback = '\n'.join(['Traceback (most recent call last):'] + ['  line %d' % n for n in range(10)] +
                          ['AssertionError: 0.6 != 0.5'])
    write(tmp_path, 'rosunit-square.xml', [('corners', '<failure message="AssertionError: 0.6 != 0.5">%s</failure>'
                                            % traceback)])
    write(tmp_path, 'rostest-test_square.xml', [('testsquare', '')])
    out = run_counter(tmp_path)[2]
    assert 'FAILED: t.corners\n' + ''.join('      line %d\n' % n for n in range(5, 10)) + \
        '    AssertionError: 0.6 != 0.5\n' in out
    assert 'Traceback' not in out and out.count('0.6 != 0.5') == 1


def test_a_rosunit_failure_shows_the_values_it_begins_with_above_its_traceback(tmp_path):
    # rosunit writes the assertion's message first, then the traceback, which ends at the test's line.
    text = '\n'.join(['17.38 != 50.0 within 0.5 delta : the clock holding at the end: False'] +
                     ['  File "case.py", line %d, in run' % n for n in range(10)])
    write(tmp_path, 'rosunit-held.xml', [('rate', '<failure type="AssertionError">%s</failure>' % text)])
    write(tmp_path, 'rostest-test_held.xml', [('testheld', '')])
    out = run_counter(tmp_path)[2]
    assert 'FAILED: t.rate\n    17.38 != 50.0 within 0.5 delta : the clock holding at the end: False\n' + \
        ''.join('      File "case.py", line %d, in run\n' % n for n in range(4, 10)) in out


def test_a_rostest_whose_node_died_counts_as_failed(tmp_path):
    write(tmp_path, 'rostest-test_square.xml', [('testsquare', '<failure message="no results"/>')])
    assert run_counter(tmp_path)[:2] == (1, '0 passed, 1 failed')


def test_passing_pytest_and_rostest_cases_are_counted_once(tmp_path):
    write(tmp_path, 'pytest.xml', [('a', ''), ('b', '')])
    write(tmp_path, 'rosunit-x.xml', [('c', '')])
    write(tmp_path, 'rostest-test_x.xml', [('testx', '')])
    assert run_counter(tmp_path)[:2] == (0, '3 passed, 0 failed')


def test_skipped_cases_are_reported_and_fail_the_run(tmp_path):
    write(tmp_path, 'pytest.xml', [('a', ''), ('b', '<skipped/>')])
    assert run_counter(tmp_path)[:2] == (1, '1 passed, 0 failed, 1 skipped')


def test_a_step_that_failed_before_writing_results_is_a_failure(tmp_path):
    write(tmp_path, 'pytest.xml', [('a', '')])
    code, last, out = run_counter(tmp_path, 'building the tests')
    assert (code, last) == (1, '1 passed, 1 failed') and 'FAILED: building the tests' in out


def test_no_results_at_all_is_not_a_pass(tmp_path):
    assert run_counter(tmp_path)[:2] == (1, '0 passed, 0 failed')


def test_an_expected_result_file_that_is_missing_fails_the_run(tmp_path):
    write(tmp_path, 'pytest.xml', [('a', '')])
    code, last, out = run_counter(tmp_path, '--expect', 'pytest/turtlesim.xml')
    assert (code, last) == (1, '1 passed, 1 failed')
    assert 'FAILED: pytest/turtlesim.xml: no test results' in out


def test_an_expected_result_file_without_test_cases_fails_the_run(tmp_path):
    write(tmp_path, 'pytest.xml', [('a', '')])
    write(tmp_path, 'empty.xml', [])  # pytest's file when it collected nothing
    assert run_counter(tmp_path, '--expect', 'empty.xml')[:2] == (1, '1 passed, 1 failed')


def test_a_passing_rostest_wrapper_without_the_nodes_results_fails(tmp_path):
    write(tmp_path, 'rostest-test_square.xml', [('testsquare', '')])
    code, last, out = run_counter(tmp_path, '--expect', 'rostest-test_square.xml')
    assert (code, last) == (1, '0 passed, 1 failed')
    assert 'test node square passed but left no test cases in rosunit-square.xml' in out


def test_expected_files_that_are_there_count_as_usual(tmp_path):
    write(tmp_path, 'rosunit-square.xml', [('corners', '')])
    write(tmp_path, 'rostest-test_square.xml', [('testsquare', '')])
    assert run_counter(tmp_path, '--expect', 'rostest-test_square.xml')[:2] == (0, '1 passed, 0 failed')
