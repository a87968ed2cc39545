#!/usr/bin/env python3
"""Counts the JUnit results (pytest and rostest) below a folder and prints `N passed, N failed`.

Usage: count_results.py RESULTS_DIR [--expect FILE]... [FAILED_STEP]...
  --expect FILE  a result file (relative to RESULTS_DIR) that a step of the run was to write, with at
                 least one test case in it: pytest/<package>.xml, <package>/rostest-test_<name>.xml.
                 A missing or empty one is a failure: a step that found no tests proves nothing.
  FAILED_STEP    a sentence naming a step that failed before it could write results.

Every <testcase> counts once. A test case with <failure> or <error> failed (its last lines are
printed under its name: CI's output is often all there is of a run); a <skipped> one is
reported as skipped, and skips fail the run too: a test that did not run proves nothing.
rostest writes two files per .test: rosunit-<test>.xml with the test node's own cases (the ones that
count), and rostest-<file>.xml with one wrapper case `test<test>` per test node, which records no
failure of those cases but does fail when the test node crashed or timed out without results. So the
wrapper counts only when it failed (a passing wrapper would count every .test file twice), and a
passing wrapper whose rosunit-<test>.xml is missing or holds no case is a failure.
Exit status: 0 when everything passed, 1 otherwise.
"""
import os
import sys
import xml.etree.ElementTree as ET


def result_files(folder):
    for parent, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith('.xml'):
                yield os.path.join(parent, name)


def test_cases(path):
    """The <testcase> elements of a result file, or None when it is missing or unreadable."""
    try:
        return list(ET.parse(path).getroot().iter('testcase'))
    except (OSError, ET.ParseError):
        return None


# How many lines of a failure's message and traceback are printed under its name.
WHY_LINES = 6


def why_it_failed(case):
    """A failed case's <failure> or <error> (message and text), indented: its first line and its last
    lines. pytest ends the text with the assertion's values; rosunit begins it with them and ends it
    with the traceback."""
    found = case.find('failure')
    found = found if found is not None else case.find('error')
    text = '%s\n%s' % (found.get('message') or '', found.text or '')
    lines = [line.rstrip()[:300] for line in text.replace('<![CDATA[', '').replace(']]>', '').splitlines()
             if line.strip()]
    shown = lines[-WHY_LINES:]
    if lines and lines[0] not in shown:
        shown.insert(0, lines[0])
    return ''.join('\n    ' + line for line in shown)


def count(folder, expected=()):
    passed, failed, skipped = [], [], []
    for path in result_files(folder):
        cases = test_cases(path)
        if cases is None:
            failed.append('%s (unreadable result file)' % path)
            continue
        wrapper = os.path.basename(path).startswith('rostest-')
        for case in cases:
            name = '%s.%s' % (case.get('classname', '?'), case.get('name', '?'))
            if case.find('failure') is not None or case.find('error') is not None:
                failed.append(name + why_it_failed(case))
            elif wrapper:
                failed.extend(_missing_node_results(path, case.get('name', '')))
            elif case.find('skipped') is not None:
                skipped.append(name)
            else:
                passed.append(name)
    for relative in expected:
        if not test_cases(os.path.join(folder, relative)):
            failed.append('%s: no test results (the step found no tests, or wrote none)' % relative)
    return passed, failed, skipped


def _missing_node_results(wrapper_path, wrapper_case):
    """A passing rostest wrapper case `test<node>` stands for rosunit-<node>.xml: it must hold cases."""
    node = wrapper_case[len('test'):] if wrapper_case.startswith('test') else wrapper_case
    node_results = os.path.join(os.path.dirname(wrapper_path), 'rosunit-%s.xml' % node)
    if test_cases(node_results):
        return []
    return ['%s: test node %s passed but left no test cases in %s'
            % (wrapper_path, node, os.path.basename(node_results))]


def parse_arguments(argv):
    folder, expected, steps = argv[0], [], []
    rest = iter(argv[1:])
    for argument in rest:
        if argument == '--expect':
            expected.append(next(rest, None))
            if expected[-1] is None:
                raise SystemExit('count_results: --expect needs a file name')
        else:
            steps.append(argument)
    return folder, expected, steps


def main(argv):
    if not argv or argv[0].startswith('-'):
        print(__doc__.split('\n\n')[1], file=sys.stderr)
        return 2
    folder, expected, failed_steps = parse_arguments(argv)
    passed, failed, skipped = count(folder, expected)
    failed += failed_steps
    for name in failed:
        print('FAILED: %s' % name)
    for name in skipped:
        print('SKIPPED (counts as not passed): %s' % name)
    line = '%d passed, %d failed' % (len(passed), len(failed))
    if skipped:
        line += ', %d skipped' % len(skipped)
    print(line)
    return 0 if passed and not failed and not skipped else 1


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
