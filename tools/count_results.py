#!/usr/bin/env python3
"""Counts the JUnit results (pytest and rostest) below a folder and prints `N passed, N failed`.

Every <testcase> counts once. A test case with <failure> or <error> failed; a <skipped> one is
reported as skipped, and skips fail the run too: a test that did not run proves nothing.
rostest writes two files per .test: rosunit-<test>.xml with the test node's own cases (the ones that
count), and rostest-<file>.xml with one wrapper case that records no failure of those cases but does
fail when the test node crashed or timed out without results. So the wrapper counts only when it
failed; a passing wrapper would count every .test file twice.
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


def count(folder):
    passed, failed, skipped = [], [], []
    for path in result_files(folder):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            failed.append('%s (unreadable result file: %s)' % (path, err))
            continue
        wrapper = os.path.basename(path).startswith('rostest-')
        for case in root.iter('testcase'):
            name = '%s.%s' % (case.get('classname', '?'), case.get('name', '?'))
            if case.find('failure') is not None or case.find('error') is not None:
                failed.append(name)
            elif wrapper:
                continue
            elif case.find('skipped') is not None:
                skipped.append(name)
            else:
                passed.append(name)
    return passed, failed, skipped


def main():
    folder = sys.argv[1]
    extra_failures = sys.argv[2:]  # steps that failed before producing results
    passed, failed, skipped = count(folder)
    failed += extra_failures
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
    sys.exit(main())
