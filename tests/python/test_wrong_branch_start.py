"""Wrong-branch starts (training/guidewire_nav/wrong_branch_start.py): a share of training episodes begins with the
tip inside a wrong child, seeded; refused where the task or layout cannot have such a start; gw-train runs with it
(the anchor's mask: test_train_smoke.py)."""

import json
from pathlib import Path

import numpy as np
import pytest

from guidewire_nav.env import GuidewireEnv, find_server_binary

REPO = Path(__file__).resolve().parents[2]
GENERALIST = json.loads((REPO / "training" / "tasks" / "generalist.json").read_text())


@pytest.fixture(scope="module")
def server_env():
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    env = GuidewireEnv(anatomies="t1_straight_y", server_args=["--task", json.dumps(GENERALIST)])
    yield env
    env.close()


def test_every_start_inside_a_wrong_child_at_fraction_one_and_seeded(server_env):
    from guidewire_nav.wrong_branch_start import WrongBranchStart

    env = WrongBranchStart(server_env, 1.0)
    flag = env.observation_names.index("wrong_branch")
    first = []
    for seed in range(3):
        obs, info = env.reset(seed=seed)
        assert info["wrong_branch_start"] and info["lead_in_steps"] > 0 and obs[flag] == 1.0
        first.append(obs)
        # the state is one a controller can leave: pulling takes the tip out of the wrong child again
        for _ in range(60):
            obs, _, terminated, truncated, _ = env.step(np.array([0.0, -1.0], dtype=np.float32))
            assert not (terminated or truncated)
            if obs[flag] == 0.0:
                break
        assert obs[flag] == 0.0
    again = [env.reset(seed=seed)[0] for seed in range(3)]
    assert all(np.array_equal(a, b) for a, b in zip(first, again))  # the same seed, the same start
    assert env.started_in_wrong_branch == 6 and env.lead_ins_dropped == 0


def test_pulled_back_starts_leave_the_tip_short_of_the_fork_aimed_into_the_wrong_child(server_env):
    from guidewire_nav.wrong_branch_start import WrongBranchStart

    env = WrongBranchStart(server_env, 1.0, pullback_steps=15)
    flag = env.observation_names.index("wrong_branch")
    omega = env.observation_names.index("omega")
    pulled = []
    for seed in range(8):
        obs, info = env.reset(seed=seed)
        assert info["wrong_branch_start"] and -15 <= info["offset_steps"] <= WrongBranchStart.DEEPER_STEPS
        assert obs[flag] == (1.0 if info["offset_steps"] >= 0 else 0.0)
        if info["offset_steps"] < 0:
            pulled.append((seed, obs))
            assert obs[omega] > 0.0  # still aimed away from the target's child: the rotation was held
            # pushed on as it is aimed, the tip goes back into the wrong child
            for _ in range(60):
                obs, _, terminated, truncated, _ = env.step(np.array([0.0, 1.0], dtype=np.float32))
                if obs[flag] == 1.0 or terminated or truncated:
                    break
            assert obs[flag] == 1.0
    assert pulled, "no offset drawn below 0 in 8 seeds"
    assert all(np.array_equal(obs, env.reset(seed=seed)[0]) for seed, obs in pulled)  # seeded
    assert env.lead_ins_dropped == 0


def test_fraction_zero_is_the_ordinary_reset(server_env):
    from guidewire_nav.wrong_branch_start import WrongBranchStart

    plain, _ = server_env.reset(seed=5)
    obs, info = WrongBranchStart(server_env, 0.0).reset(seed=5)
    assert np.array_equal(plain, obs) and "wrong_branch_start" not in info


def test_refused_without_the_flag_the_act2_action_or_recovery():
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    from guidewire_nav.wrong_branch_start import WrongBranchStart

    with GuidewireEnv(anatomies="t1_straight_y") as rotation_only:  # obs/3, act/1: the shipped actor's task
        with pytest.raises(ValueError, match="need an observation with omega and wrong_branch"):
            WrongBranchStart(rotation_only, 0.5)
    strict = {**GENERALIST, "recovery_attempts": 0}
    with GuidewireEnv(anatomies="t1_straight_y", server_args=["--task", json.dumps(strict)]) as env:
        with pytest.raises(ValueError, match="recovery_attempts > 0"):
            WrongBranchStart(env, 0.5)
        with pytest.raises(ValueError, match=r"within \[0, 1\]"):
            WrongBranchStart(env, 1.5)
        with pytest.raises(ValueError, match=r"pull-back must be >= 0"):
            WrongBranchStart(env, 0.5, pullback_steps=-1)


def test_gw_train_runs_with_wrong_branch_starts(tmp_path):
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    from guidewire_nav import train

    argv = ["--out", str(tmp_path), "--anatomies", "t1_straight_y", "--task", json.dumps(GENERALIST),
            "--total-steps", "120", "--learning-starts", "60", "--envs", "1", "--eval-episodes", "0",
            "--checkpoint-every", "1000", "--no-progress", "--net-arch", "32,32", "--wrong-branch-starts", "1",
            "--anchor-weight", "1", "--wrong-branch-pullback", "10"]
    assert train.main(argv) == 0
    settings = json.loads((tmp_path / "settings.json").read_text())
    assert settings["wrong_branch_starts"] == 1.0 and settings["wrong_branch_pullback"] == 10
    with pytest.raises(SystemExit, match="give --wrong-branch-starts"):
        train.parse_settings(["--wrong-branch-pullback", "5"])
