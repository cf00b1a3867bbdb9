"""guidewire_nav.feasibility: rotation-only schedules tell a reachable target from one no schedule reaches."""

import json

import pytest

from guidewire_nav import feasibility
from guidewire_nav.env import find_server_binary


@pytest.fixture(scope="module", autouse=True)
def server_built():
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")


def test_aiming_reaches_a_y_branch_and_the_report_says_so(tmp_path, capsys):
    out = tmp_path / "f.json"
    assert feasibility.main(["--cases", "t1_straight_y:1", "--seeds", "1", "--schedules", "aim-0.95,spin+1",
                             "--out", str(out)]) == 0
    report = json.loads(out.read_text())
    case = report["cases"][0]
    assert case["anatomy"] == "t1_straight_y" and case["target"] == 1
    assert set(case["successes"]) == {"aim-0.95", "spin+1"}
    assert case["successes"]["aim-0.95"] == 1 and case["reachable"]
    assert json.loads(capsys.readouterr().out.strip().splitlines()[-1]) == report


def test_bad_cases_and_schedules_are_refused():
    with pytest.raises(SystemExit):
        feasibility.main(["--cases", "t1_straight_y"])
    with pytest.raises(SystemExit):
        feasibility.main(["--cases", "t1_straight_y:1", "--schedules", "teleport"])
