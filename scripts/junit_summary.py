#!/usr/bin/env python3
"""Counts the test cases of every JUnit XML file under a directory.

Prints "TOTAL FAILED SKIPPED" on one line, for scripts/test.sh (catkin's test_results) and
scripts/test_no_ros.sh (ctest's gtest XML). A file that cannot be parsed counts as one failed
case: a test that crashed mid-write must not disappear from the count.
"""
import pathlib
import sys
import xml.etree.ElementTree as ET


def count(directory):
    total = failed = skipped = 0
    for path in pathlib.Path(directory).rglob("*.xml"):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError:
            total += 1
            failed += 1
            continue
        for case in root.iter("testcase"):
            total += 1
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
            elif case.find("skipped") is not None or case.get("result") == "skipped":
                skipped += 1
    return total, failed, skipped


if __name__ == "__main__":
    print(*count(sys.argv[1]))
