#!/usr/bin/env python3
"""Counts the test cases of every JUnit XML file under a directory.

Prints "TOTAL FAILED SKIPPED" on one line, for scripts/test.sh (catkin's test_results) and
scripts/test_no_ros.sh (ctest's gtest XML). A suite counts as many failures as the larger of
its failing <testcase> elements and its own failures + errors attributes: rosunit's writer can
mark a suite failed without a failing case (a failed unittest subTest is reported that way),
and catkin_test_results, which decides the exit status, reads the attributes. A file that
cannot be parsed counts as one failed case: a test that crashed mid-write must not disappear
from the count.
"""
import pathlib
import sys
import xml.etree.ElementTree as ET


def count_suite(suite):
    cases = suite.findall("testcase")
    failed = sum(1 for case in cases
                 if case.find("failure") is not None or case.find("error") is not None)
    skipped = sum(1 for case in cases
                  if case.find("failure") is None and case.find("error") is None
                  and (case.find("skipped") is not None or case.get("result") == "skipped"))
    declared_failed = int(suite.get("failures", 0) or 0) + int(suite.get("errors", 0) or 0)
    failed = max(failed, declared_failed)
    total = max(len(cases), int(suite.get("tests", 0) or 0), failed)
    return total, failed, skipped


def count(directory):
    total = failed = skipped = 0
    for path in pathlib.Path(directory).rglob("*.xml"):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError:
            total += 1
            failed += 1
            continue
        suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
        for suite in suites:
            suite_total, suite_failed, suite_skipped = count_suite(suite)
            total += suite_total
            failed += suite_failed
            skipped += suite_skipped
    return total, failed, skipped


if __name__ == "__main__":
    print(*count(sys.argv[1]))
