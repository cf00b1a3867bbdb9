"""Under scripts/test.sh (GW_TESTS_STRICT=1) no test may skip.

The tests skip when a binary they drive is not built, which is right for someone running one file
by hand but would let CI pass without running them (a wrong GW_BUILD_DIR skips almost everything).
"""
import os

import pytest


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.skipped and os.environ.get("GW_TESTS_STRICT") == "1":
        report.outcome = "failed"
        report.longrepr = f"skipped, and GW_TESTS_STRICT=1 forbids skips: {report.longrepr}"
