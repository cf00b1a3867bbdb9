"""Shared test plumbing.

Under scripts/test.sh (GW_TESTS_STRICT=1) no test may skip. The tests skip when a binary they drive
is not built, which is right for someone running one file by hand but would let CI pass without
running them (a wrong GW_BUILD_DIR skips almost everything).
"""
import json
import os
import subprocess
from pathlib import Path

import pytest

import guidewire_nav

REPO = Path(__file__).resolve().parents[2]


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    # An expected failure (xfail) also reports as skipped; it is not a skip and stays as it is (pytest
    # would print it as FAILED yet not count it, so the run would pass while saying it failed).
    if report.skipped and not hasattr(report, "wasxfail") and os.environ.get("GW_TESTS_STRICT") == "1":
        report.outcome = "failed"
        report.longrepr = f"skipped, and GW_TESTS_STRICT=1 forbids skips: {report.longrepr}"


@pytest.fixture
def navigate_episode(tmp_path):
    """run(controller) -> (observations, actions, omega's index) of one C++ `navigate` episode (t1_straight_y,
    target 1, seed 3) from its trajectory JSON (the index from its observation_names). Frame 0 is the reset;
    frame k+1 holds the action taken on frame k."""
    navigate = guidewire_nav.app_path("navigate")
    if not navigate.is_file():
        pytest.skip(f"navigate not built ({navigate}); set GW_BUILD_DIR")

    def run(controller: str):
        subprocess.run([str(navigate), "--anatomy", str(REPO / "anatomies/train/t1_straight_y/t1_straight_y.stl"),
                        "--target", "1", "--episodes", "1", "--seed", "3", "--controller", controller,
                        "--out", str(tmp_path)], check=True, capture_output=True)
        trace = json.loads((tmp_path / "episode0_target1.json").read_text())
        frames = trace["frames"]
        return frames["observation"], frames["action"], trace["observation_names"].index("omega")

    return run


@pytest.fixture
def navigate_frames(tmp_path):
    """run(controller, anatomy, target, seed) -> the frames of one C++ `navigate` episode (its trajectory JSON):
    observation, action, agent_in_control, ... Frame 0 is the reset; frame j >= 1 holds the action taken on
    frame j-1's observation and whether the task applied it (agent_in_control)."""
    navigate = guidewire_nav.app_path("navigate")
    if not navigate.is_file():
        pytest.skip(f"navigate not built ({navigate}); set GW_BUILD_DIR")

    def run(controller: str, anatomy: str, target: int, seed: int):
        out = tmp_path / f"{controller}_{target}_{seed}"
        subprocess.run([str(navigate), "--anatomy", str(REPO / anatomy), "--target", str(target), "--episodes", "1",
                        "--seed", str(seed), "--controller", controller, "--out", str(out)],
                       check=True, capture_output=True)
        trace = json.loads((out / f"episode0_target{target}.json").read_text())
        return {**trace["frames"], "omega_index": trace["observation_names"].index("omega")}

    return run


def app_or_skip(name: str) -> str:
    """The path of C++ app `name` (guidewire_nav.app_path), skipping the test when it is not built."""
    path = guidewire_nav.app_path(name)
    if not path.is_file():
        pytest.skip(f"{name} not built ({path}); set GW_BUILD_DIR")
    return str(path)
