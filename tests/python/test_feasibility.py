"""guidewire_nav.feasibility: rotation-only schedules tell a reachable target from one no schedule reaches."""

import json

import numpy as np
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



@pytest.mark.parametrize("name", sorted(feasibility.SCHEDULES))
def test_each_schedule_acts_as_its_cpp_namesake(navigate_episode, name):
    """The schedules are written twice (here and lib/runner/rotation_schedules.cpp): replaying the
    observations of a C++ episode through the Python rule must give the C++ actions, step by step."""
    observations, actions, omega = navigate_episode(name)
    assert len(actions) > 100  # frame 0 is the reset (no action); frame k+1 holds the action taken on frame k
    python = [feasibility.SCHEDULES[name](observations[k][omega], k) for k in range(len(actions) - 1)]
    assert python == pytest.approx(actions[1:], abs=1e-9)
    if name.startswith("aim"):  # both branches of the rule were exercised: turning and holding
        assert 0.0 in python and any(a != 0.0 for a in python)


@pytest.mark.parametrize("name", sorted(feasibility.SCHEDULES))
def test_each_schedule_counts_like_its_cpp_namesake_on_a_tree(navigate_frames, name):
    """On a tree the task asks for an action only near a bifurcation. The C++ schedules count the actions asked
    for; the Python ones must count the same (k = actions applied so far), or spin/wiggle drift apart after the
    first stretch out of control."""
    frames = navigate_frames(name, "anatomies/test/unseen_4_bifurcations/unseen_4_bifurcations.stl", 4, 0)
    obs, actions, control = frames["observation"], frames["action"], frames["agent_in_control"]
    applied = [j for j in range(1, len(actions)) if control[j]]
    assert 20 < len(applied) < len(actions) - 20  # control was handed over and back: out-of-control stretches
    omega = frames["omega_index"]
    python = [feasibility.SCHEDULES[name](obs[j - 1][omega], k) for k, j in enumerate(applied)]
    assert python == pytest.approx([actions[j] for j in applied], abs=1e-9)


class _HandOverEnv:
    """An env whose task applies every other action (in_control alternates), recording what it was sent."""

    omega_index = 9

    def __init__(self, steps: int):
        self.steps, self.sent, self.t = steps, [], 0

    def reset(self, seed=None, options=None):
        self.t = 0
        return np.zeros(11), {"in_control": True}

    def step(self, action):
        self.sent.append(float(action[0]))
        self.t += 1
        done = self.t >= self.steps
        return np.zeros(11), 0.0, done, False, {"in_control": self.t % 2 == 0, "success": done}


def test_run_episode_counts_only_applied_actions():
    env, seen = _HandOverEnv(8), []

    def schedule(omega, k):
        seen.append(k)
        return 1.0 + k

    assert feasibility.run_episode(env, "any", 1, 0, schedule)
    assert seen == [0, 1, 2, 3]  # asked on the 4 applied steps, k counting them
    assert env.sent == [1.0, 0.0, 2.0, 0.0, 3.0, 0.0, 4.0, 0.0]
