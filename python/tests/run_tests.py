#!/usr/bin/env python3
"""Runs the Python module's pytest suite (python/tests) and writes its JUnit file.

Usage: run_tests.py [--ros] JUNIT_XML
--ros: the module is the ROS workspace's package, which must also hold the generated messages.
Exits with pytest's status, except that a run that collected no test fails (pytest's 5): the
suite always has tests, so none means something is wrong with the run.
"""
import os
import pathlib
import sys

import pytest


def main(argv):
    ros = "--ros" in argv
    xml = [arg for arg in argv if arg != "--ros"][0]
    if ros:
        os.environ["SAP_EXPECT_ROS_MESSAGES"] = "1"
    status = pytest.main([str(pathlib.Path(__file__).resolve().parent), "-q", "-p",
                          "no:cacheprovider", "--junitxml=" + xml])
    if status == pytest.ExitCode.NO_TESTS_COLLECTED:
        print("run_tests.py: pytest collected no test", file=sys.stderr)
        return 1
    return int(status)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
