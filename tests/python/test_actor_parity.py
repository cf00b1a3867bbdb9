"""Parity: the C++ Eigen actor (policy-run) equals SB3's predict(deterministic=True) to 1e-5."""

import subprocess
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import torch

from guidewire_nav import app_path
from guidewire_nav.export_actor import export_sac_actor


def _policy_run() -> Path:
    binary = app_path("policy-run")
    if not binary.is_file():
        pytest.skip(f"policy-run binary not built ({binary}; set GW_BUILD_DIR)")
    return binary


class BoxEnv(gym.Env):
    def __init__(self, obs_size=20, low=(-2.0, 0.5), high=(1.0, 3.0)):
        self.observation_space = gym.spaces.Box(-5.0, 5.0, (obs_size,), np.float32)
        self.action_space = gym.spaces.Box(np.array(low, np.float32), np.array(high, np.float32))

    def reset(self, seed=None, options=None):
        super().reset(seed=seed)
        return np.zeros(self.observation_space.shape, np.float32), {}

    def step(self, action):
        return np.zeros(self.observation_space.shape, np.float32), 0.0, False, False, {}


def _model(net_arch, env, seed=0, activation=torch.nn.ReLU):
    from stable_baselines3 import SAC

    kwargs = {"activation_fn": activation}
    if net_arch is not None:
        kwargs["net_arch"] = net_arch
    model = SAC("MlpPolicy", env, policy_kwargs=kwargs, seed=seed, device="cpu")
    with torch.no_grad():  # bigger mu so tanh is exercised away from its linear part
        model.policy.actor.mu.weight.mul_(20.0)
        model.policy.actor.mu.bias.normal_(0.0, 0.5)
    return model


def _run(binary, policy_json, obs):
    text = "\n".join(" ".join(f"{v:.9g}" for v in row) for row in obs) + "\n"
    res = subprocess.run([str(binary), "--policy", str(policy_json)], input=text, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    return np.array([[float(v) for v in line.split()] for line in res.stdout.splitlines()])


@pytest.mark.parametrize(
    "net_arch,activation", [([256, 256, 256], torch.nn.ReLU), (None, torch.nn.ReLU), ([64, 32], torch.nn.Tanh)]
)
def test_parity_random_weights(tmp_path, net_arch, activation):
    binary = _policy_run()
    env = BoxEnv()
    model = _model(net_arch, env, activation=activation)
    n_hidden = len(net_arch) if net_arch else 2  # SB3's default is 2x256
    out = tmp_path / "actor.json"
    d = export_sac_actor(model, out, obs_layout="test/1", training_settings={"net_arch": net_arch})
    assert len(d["layers"]) == n_hidden + 1
    assert d["action_layout"] == "guidewire-nav/act/2"  # two actions, as the push/pull actor's (by the size)
    rng = np.random.default_rng(1)
    obs = rng.normal(0, 2, (1000, 20)).astype(np.float32)
    expected, _ = model.predict(obs, deterministic=True)
    got = _run(binary, out, obs)
    assert got.shape == expected.shape
    assert np.all(got >= env.action_space.low - 1e-6) and np.all(got <= env.action_space.high + 1e-6)
    assert np.max(np.abs(got - expected)) < 1e-5
    assert np.std(expected[:, 0]) > 0.1  # the test sees varied, non-saturated actions


def test_parity_with_vecnormalize(tmp_path):
    from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

    binary = _policy_run()
    venv = VecNormalize(DummyVecEnv([BoxEnv]), norm_obs=True, norm_reward=False, clip_obs=3.0)
    rng = np.random.default_rng(2)
    venv.obs_rms.mean = rng.normal(0, 1, 20)
    venv.obs_rms.var = rng.uniform(0.1, 4.0, 20)
    model = _model([256, 256, 256], venv)
    stats = tmp_path / "vecnormalize.pkl"
    venv.save(str(stats))
    out = tmp_path / "actor.json"
    export_sac_actor(model, out, obs_layout="test/1", vecnormalize=str(stats))
    obs = rng.normal(0, 3, (1000, 20)).astype(np.float32)
    expected, _ = model.predict(venv.normalize_obs(obs), deterministic=True)
    got = _run(binary, out, obs)
    assert np.max(np.abs(got - expected)) < 1e-5


def test_policy_run_rejects_bad_line(tmp_path):
    binary = _policy_run()
    model = _model([8], BoxEnv(obs_size=3, low=(-1,), high=(1,)))
    out = tmp_path / "actor.json"
    export_sac_actor(model, out)
    res = subprocess.run([str(binary), "--policy", str(out)], input="1 2 3\n1 2\n", capture_output=True, text=True)
    assert res.returncode != 0 and "line 2" in res.stderr
    res = subprocess.run([str(binary), "--policy", str(out)], input="1 x 3\n", capture_output=True, text=True)
    assert res.returncode != 0 and "line 1" in res.stderr


def test_export_refuses_gsde_hardtanh(tmp_path):
    from stable_baselines3 import SAC

    model = SAC("MlpPolicy", BoxEnv(), use_sde=True, device="cpu")  # clip_mean=2.0 -> Hardtanh
    with pytest.raises(ValueError, match="Hardtanh"):
        export_sac_actor(model, tmp_path / "a.json")


def test_widened_rotation_actor_starts_the_push_pull_actor(tmp_path):
    """A rotation actor (obs/3, act/1) widened for a --push-pull run: the rotation is the shipped actor's on
    every obs/5 observation whatever the two new entries, the insertion pushes at tanh(2), torch (after
    load_actor_json) = the C++ runtime on the widened JSON = the C++ runtime on the original."""
    import json

    from guidewire_nav.export_actor import load_actor_json, widen_to_push_pull

    binary = _policy_run()
    shipped = Path(__file__).resolve().parents[2] / "policy" / "trained" / "sac_actor.json"
    original = json.loads(shipped.read_text())
    widened = widen_to_push_pull(original)
    assert (widened["obs_layout"], widened["action_layout"]) == ("guidewire-nav/obs/5", "guidewire-nav/act/2")
    (tmp_path / "widened.json").write_text(json.dumps(widened))
    rng = np.random.default_rng(3)
    obs = rng.uniform(-1, 1, (300, 14)).astype(np.float32)
    obs[:, 12] = rng.uniform(-1, 1, 300)  # last insertion
    obs[:, 13] = rng.integers(0, 2, 300)  # wrong-branch flag
    rotation = _run(binary, shipped, obs[:, :12])
    both = _run(binary, tmp_path / "widened.json", obs)
    assert np.max(np.abs(both[:, 0] - rotation[:, 0])) < 1e-6  # printed to 9 digits, summed in another order
    assert np.allclose(both[:, 1], np.tanh(2.0))
    assert np.std(rotation[:, 0]) > 0.1
    model = _model([256, 256, 256], BoxEnv(obs_size=14, low=(-1.0, -1.0), high=(1.0, 1.0)))
    load_actor_json(model, widened)
    expected, _ = model.predict(obs, deterministic=True)
    assert np.max(np.abs(expected - both)) < 1e-5
    with pytest.raises(ValueError, match="obs/3 rotation actor"):
        widen_to_push_pull(widened)


def test_widened_push_pull_actor_starts_the_tip_force_actor(tmp_path):
    """The shipped push/pull actor (obs/5) widened for an obs/8 task: both outputs are the original's on every obs/8
    observation whatever the tip force, in the C++ runtime, which reads the new layout's 15 entries."""
    import json

    from guidewire_nav.export_actor import widen_to_tip_force

    binary = _policy_run()
    shipped = Path(__file__).resolve().parents[2] / "policy" / "trained" / "sac_actor_push_pull.json"
    original = json.loads(shipped.read_text())
    widened = widen_to_tip_force(original)
    assert (widened["obs_layout"], widened["obs_size"]) == ("guidewire-nav/obs/8", 15)
    (tmp_path / "widened.json").write_text(json.dumps(widened))
    rng = np.random.default_rng(4)
    obs = rng.uniform(-1, 1, (300, 15)).astype(np.float32)
    obs[:, 13] = rng.integers(0, 2, 300)  # wrong-branch flag
    obs[:, 14] = rng.uniform(0, 4, 300)  # tip force over 1.5 N
    before = _run(binary, shipped, obs[:, :14])
    after = _run(binary, tmp_path / "widened.json", obs)
    assert np.max(np.abs(after - before)) < 1e-6
    with pytest.raises(ValueError, match="obs/5 push/pull actor"):
        widen_to_tip_force(widened)


def test_widen_for_task_widens_as_the_task_needs():
    """The start of a task of given layouts: a rotation actor for obs/8 act/2 is widened twice (rotation kept, the
    insertion pushing, two and one new inputs), for obs/5 act/2 once; a push/pull actor in its own task is untouched."""
    import json

    from guidewire_nav.export_actor import widen_for_task, widen_to_push_pull, widen_to_tip_force

    trained = Path(__file__).resolve().parents[2] / "policy" / "trained"
    rotation = json.loads((trained / "sac_actor.json").read_text())
    push_pull = json.loads((trained / "sac_actor_push_pull.json").read_text())
    both = widen_for_task(rotation, "guidewire-nav/obs/8", "guidewire-nav/act/2")
    assert both == widen_to_tip_force(widen_to_push_pull(rotation)) and both["obs_size"] == 15
    assert widen_for_task(rotation, "guidewire-nav/obs/5", "guidewire-nav/act/2") == widen_to_push_pull(rotation)
    assert widen_for_task(push_pull, "guidewire-nav/obs/5", "guidewire-nav/act/2") is push_pull
