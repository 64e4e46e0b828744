#!/usr/bin/env python3
"""Runs one pytest file (or pytest with these arguments) for `meson test`: exit 77 (skipped) when pytest or
NumPy is missing or the build sets PW85_PYTHON_TEST_SKIP, and when every
test of the file was skipped (or the file skipped itself, pytest's status
5); pytest's exit status otherwise. (The main
guard matters: Dask's worker processes re-import this __main__.)

usage: run_pytest.py TESTFILE|PYTEST-ARGUMENT...
"""
import os
import sys


class Count:
    """Outcomes of the tests that ran or were skipped."""

    def __init__(self):
        self.outcomes = []

    def pytest_runtest_logreport(self, report):
        if report.when == "call" or report.outcome == "skipped":
            self.outcomes.append(report.outcome)


def main():
    reason = os.environ.get("PW85_PYTHON_TEST_SKIP")
    if reason:
        print("SKIP: " + reason)
        return 77
    try:
        import numpy  # noqa: F401
        import pytest
    except ImportError as e:
        print(f"SKIP: {e} ({sys.executable})")
        return 77
    count = Count()
    status = pytest.main(["-q", "-rs", "-p", "no:cacheprovider"] + sys.argv[1:], plugins=[count])
    if status == 0 and count.outcomes and all(o == "skipped" for o in count.outcomes):
        return 77
    if status == pytest.ExitCode.NO_TESTS_COLLECTED:
        return 77
    return int(status)


if __name__ == "__main__":
    sys.exit(main())
