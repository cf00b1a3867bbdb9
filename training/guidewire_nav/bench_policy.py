"""Time per action of the same SAC actor in torch, onnxruntime (if installed) and the Eigen runtime.

python -m guidewire_nav.bench_policy [--obs-size 20] [--calls 20000] [--build-dir DIR]
Prints ONE JSON object. A 3x256 actor (paper size) with random weights; single observation,
no grad, CPU, one thread for every runtime.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import tempfile
import time
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch

from guidewire_nav import app_path
from guidewire_nav.export_actor import export_sac_actor


class _Env(gym.Env):
    def __init__(self, obs_size: int):
        self.observation_space = gym.spaces.Box(-np.inf, np.inf, (obs_size,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (1,), np.float32)

    def reset(self, seed=None, options=None):
        return np.zeros(self.observation_space.shape, np.float32), {}

    def step(self, action):
        return np.zeros(self.observation_space.shape, np.float32), 0.0, False, False, {}


class _Deterministic(torch.nn.Module):
    """tanh(mu(latent_pi(obs))) in [-1, 1]; rescaling is identity for a [-1, 1] box."""

    def __init__(self, actor):
        super().__init__()
        self.latent_pi, self.mu = actor.latent_pi, actor.mu

    def forward(self, obs):
        return torch.tanh(self.mu(self.latent_pi(obs)))


def _time(fn, calls: int) -> float:
    for _ in range(min(1000, calls)):
        fn()
    t0 = time.perf_counter()
    for _ in range(calls):
        fn()
    return (time.perf_counter() - t0) / calls * 1e9


def _bench_binary(build_dir: str | None) -> Path:
    binary = Path(build_dir) / "apps" / "bench-policy" if build_dir else app_path("bench-policy")
    if not binary.is_file():
        raise SystemExit(f"bench_policy: {binary} not found; build it, or pass --build-dir or set GW_BUILD_DIR")
    return binary


def main(argv=None) -> None:
    from stable_baselines3 import SAC

    p = argparse.ArgumentParser(description="Benchmark the SAC actor: torch vs onnxruntime vs Eigen")
    p.add_argument("--obs-size", type=int, default=20, help="observation size of the random actor")
    p.add_argument("--calls", type=int, default=20000, help="timed actions per runtime")
    p.add_argument("--build-dir", help="build folder holding apps/bench-policy (default: $GW_BUILD_DIR or build/)")
    a = p.parse_args(argv)
    torch.set_num_threads(1)
    model = SAC("MlpPolicy", _Env(a.obs_size), policy_kwargs={"net_arch": [256, 256, 256]}, device="cpu", seed=0)
    net = _Deterministic(model.policy.actor).eval()
    obs = np.random.default_rng(0).normal(size=(1, a.obs_size)).astype(np.float32)
    obs_t = torch.from_numpy(obs)
    result: dict = {"actor": f"{a.obs_size}-256-256-256-1 relu, tanh squash", "calls": a.calls}

    with torch.no_grad():
        result["torch_ns_per_action"] = _time(lambda: net(obs_t), a.calls)

    with tempfile.TemporaryDirectory() as tmp:
        try:
            import onnxruntime as ort

            onnx_path = Path(tmp) / "actor.onnx"
            torch.onnx.export(net, obs_t, str(onnx_path), input_names=["obs"], output_names=["action"], dynamo=False)
            so = ort.SessionOptions()
            so.intra_op_num_threads = 1
            so.inter_op_num_threads = 1
            sess = ort.InferenceSession(str(onnx_path), so, providers=["CPUExecutionProvider"])
            ref = net(obs_t).detach().numpy()
            assert np.allclose(sess.run(None, {"obs": obs})[0], ref, atol=1e-5)
            result["onnxruntime_ns_per_action"] = _time(lambda: sess.run(None, {"obs": obs}), a.calls)
        except ImportError:
            result["onnxruntime_ns_per_action"] = None
            result["onnxruntime_note"] = "onnxruntime not installed (pip install guidewire-nav[bench])"

        json_path = Path(tmp) / "actor.json"
        export_sac_actor(model, json_path, obs_layout="bench")
        binary = _bench_binary(a.build_dir)
        eigen_calls = max(a.calls, 100000)
        out = subprocess.run([str(binary), "--policy", str(json_path), "--calls", str(eigen_calls)],
                             capture_output=True, text=True, check=True)
        eig = json.loads(out.stdout)
        result["eigen_ns_per_action"] = eig["ns_per_action"]
        result["eigen_calls"] = eigen_calls

    for k in ("torch", "onnxruntime", "eigen"):
        v = result.get(f"{k}_ns_per_action")
        result[f"{k}_us_per_action"] = None if v is None else v / 1000.0
    result["speedup_eigen_vs_torch"] = result["torch_ns_per_action"] / result["eigen_ns_per_action"]
    if result["onnxruntime_ns_per_action"]:
        result["speedup_eigen_vs_onnxruntime"] = result["onnxruntime_ns_per_action"] / result["eigen_ns_per_action"]
    result["goal_met"] = result["eigen_us_per_action"] < 10.0 and result["speedup_eigen_vs_torch"] >= 10.0
    print(json.dumps(result))


if __name__ == "__main__":
    main()
