"""results/generalist/insertion_probe.py: what a checkpoint's actor and critics make of the insertion, on a SAC model
whose actor is set by hand (no server needed)."""
import importlib.util
import json

import gymnasium as gym
import numpy as np
import pytest
import torch
from stable_baselines3 import SAC

from guidewire_nav import REPO_ROOT

SCRIPT = REPO_ROOT / "results" / "generalist" / "insertion_probe.py"


def load_probe():
    spec = importlib.util.spec_from_file_location("insertion_probe", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Still(gym.Env):
    observation_space = gym.spaces.Box(-1, 1, (15,), np.float32)
    action_space = gym.spaces.Box(-1, 1, (2,), np.float32)

    def reset(self, seed=None, options=None):
        return np.zeros(15, np.float32), {}

    def step(self, action):
        return np.zeros(15, np.float32), 0.0, False, False, {}


def test_reports_the_actors_insertion_and_the_critics_view_of_a_push(tmp_path, capsys):
    model = SAC("MlpPolicy", Still(), learning_starts=0, buffer_size=100, gamma=0.995, policy_kwargs={"net_arch": [8]},
                device="cpu", seed=0)
    model.learn(40)
    with torch.no_grad():  # the actor's mean: rotation 0, insertion tanh(-1) = -0.76 everywhere
        model.actor.mu.weight.zero_()
        model.actor.mu.bias.copy_(torch.tensor([0.0, -1.0]))
    model.replay_buffer.observations[:10, 0, 13] = 1.0  # ten states with the wrong-branch flag raised
    model.save(tmp_path / "sac_40_steps.zip")
    model.save_replay_buffer(tmp_path / "sac_replay_buffer_40_steps.pkl")

    probe = load_probe()
    assert probe.main([str(tmp_path / "sac_40_steps.zip"), "--states", "30"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["states"] == 30 and out["gamma"] == pytest.approx(0.995)
    assert out["insertion_quantiles_5_25_50_75_95"] == [pytest.approx(np.tanh(-1.0), abs=1e-3)] * 5
    assert set(out) >= {"q_push_minus_q_own_mean", "dq_dinsertion_at_push_median", "log_std_mean", "ent_coef"}
    assert probe.main([str(tmp_path / "sac_40_steps.zip"), "--wrong-branch"]) == 0  # only those ten
    assert json.loads(capsys.readouterr().out)["states"] == 10
    with pytest.raises(SystemExit, match="no such checkpoint"):
        probe.main([str(tmp_path / "none.zip")])
