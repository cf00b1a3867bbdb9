"""Where a training step's time goes: simulation, socket, replay buffer, gradient; and whole-loop throughput.

    gw-bench-train [--envs 2] [--steps 600] [--configs shipped,fed] [--out FILE.json]

Prints ONE JSON object (and writes it to --out). Measured in this run, on this machine, with the servers of
`gw-train` (same anatomies and task settings):
  simulation   one server: ms per env step through the socket, the socket's own round trip (a 'spec'
               request), the difference = the simulator's step
  vec_env      --envs servers stepped together (SubprocVecEnv), no learning: env steps/s
  replay       the SAC replay buffer: ms to add one vector step, to sample one batch
  gradient     ms per SAC gradient step (actor, two critics, entropy coefficient) per config's batch, net
               and torch threads
  learn        per config, gw-train's loop (model.learn) for --steps env steps after a warm buffer:
               env steps/s measured, and predicted from the parts
A config is NAME=train_freq:gradient_steps:batch:net:threads (net as 256x256x256); the named ones:
  shipped  1:-1:256:256x256x256:0   the shipped training command: one gradient step per env step
  fed      4:2:256:256x256:0        2 gradient steps every 4 vector steps of 2 envs (1 per 4 env steps), 2x256 nets
  overlapped 2:2:256:256x256:0:overlap:e4   fed's ratio (1 gradient step per 4 env steps) with 4 servers and
                                           gw-train --overlap: the gradient steps while the servers simulate
A config may end in `:overlap` (gw-train --overlap) and `:eN` (N servers instead of --envs); each number of servers
gets its own vec_env measurement, the reference of the configs that use it.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import platform
import sys
import time
from pathlib import Path

import numpy as np
import torch
from stable_baselines3 import SAC
from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

from guidewire_nav.train import SACWithActorRate, Settings, git_commit, make_env_fn

DEFAULT_THREADS = torch.get_num_threads()  # torch's own default (one per core), before any config sets another
NAMED = {"shipped": "1:-1:256:256x256x256:0", "fed": "4:2:256:256x256:0", "overlapped": "2:2:256:256x256:0:overlap:e4"}


def parse_config(text: str) -> dict:
    """One --configs entry (a name of NAMED or NAME=f:g:b:net:t) -> its settings; a malformed one exits naming it."""
    name, _, spec = text.partition("=")
    spec = spec or NAMED.get(name, "")
    try:
        freq, grad, batch, net, threads, *extra = spec.split(":")
        envs = [int(e[1:]) for e in extra if e.startswith("e")]
        if [e for e in extra if e != "overlap" and not e.startswith("e")] or len(envs) > 1 or min(envs, default=1) < 1:
            raise ValueError(extra)
        return {"name": name, "train_freq": int(freq), "gradient_steps": int(grad), "batch_size": int(batch),
                "net_arch": [int(n) for n in net.split("x")], "torch_threads": int(threads),
                "overlap": "overlap" in extra, "envs": envs[0] if envs else None}
    except ValueError:
        sys.exit(f"gw-bench-train: --configs entry '{text}' is neither {sorted(NAMED)} nor "
                 "NAME=train_freq:gradient_steps:batch:net:threads[:overlap][:eN] (e.g. fast=4:2:512:256x256x256:1)")


def time_calls(fn, calls: int) -> float:
    """Mean ms of `calls` calls of fn()."""
    start = time.perf_counter()
    for _ in range(calls):
        fn()
    return 1e3 * (time.perf_counter() - start) / calls


def bench_simulation(settings: Settings, steps: int) -> dict:
    """One server through its socket: ms per step, the socket round trip, the simulator's share."""
    env = make_env_fn(settings, 0)()
    rng = np.random.default_rng(0)

    def step():
        if env.step(rng.uniform(-1, 1, env.action_space.shape))[2:4] != (False, False):
            env.reset()

    step_ms = time_calls(step, steps)
    socket_ms = time_calls(lambda: env.env._request({"cmd": "spec"}), steps)
    env.close()
    return {"step_ms": step_ms, "socket_round_trip_ms": socket_ms, "simulator_ms": step_ms - socket_ms}


def make_vec_env(settings: Settings):
    """gw-train's workers: one server each (SubprocVecEnv; in process for one)."""
    fns = [make_env_fn(settings, rank) for rank in range(settings.envs)]
    return SubprocVecEnv(fns) if settings.envs > 1 else DummyVecEnv(fns)


def bench_vec_env(vec_env, steps: int) -> dict:
    """The workers stepped together with random actions, no learning."""
    n = vec_env.num_envs
    vec_env.reset()
    actions = lambda: np.random.uniform(-1, 1, (n,) + vec_env.action_space.shape)  # noqa: E731
    ms = time_calls(lambda: vec_env.step(actions()), max(1, steps // n))
    return {"envs": n, "vector_step_ms": ms, "env_steps_per_s": 1e3 * n / ms}


def make_model(vec_env, config: dict, seed: int = 0) -> SACWithActorRate:
    """SAC with gw-train's paper settings (its Settings defaults) and the config's schedule, batch and net."""
    paper = Settings()
    return SACWithActorRate("MlpPolicy", vec_env, learning_rate=paper.learning_rate, buffer_size=paper.buffer_size,
                            batch_size=config["batch_size"], gamma=paper.gamma, learning_starts=0, train_freq=config["train_freq"],
                            gradient_steps=config["gradient_steps"], seed=seed, device="cpu", verbose=0,
                            policy_kwargs={"net_arch": config["net_arch"]}, overlap=config["overlap"])


def warm_buffer(model, transitions: int) -> None:
    """Random-action steps into the replay buffer (what learning_starts does), so that batches can be drawn."""
    model.learning_starts = transitions
    model.learn(total_timesteps=transitions, progress_bar=False)


def bench_replay(model, calls: int) -> dict:
    """ms to add one vector step and to draw one batch."""
    buffer = model.replay_buffer
    n = model.n_envs
    obs = np.zeros((n,) + model.observation_space.shape, np.float32)
    act = np.zeros((n,) + model.action_space.shape, np.float32)
    add = lambda: buffer.add(obs, obs, act, np.zeros(n), np.zeros(n), [{}] * n)  # noqa: E731
    return {"add_ms": time_calls(add, calls), "sample_ms": time_calls(lambda: buffer.sample(model.batch_size), calls)}


def bench_gradient(model, steps: int) -> float:
    """ms per gradient step at the model's batch size (SB3's update itself: an overlapped model's train only owes)."""
    update = lambda n: SAC.train(model, gradient_steps=n, batch_size=model.batch_size)  # noqa: E731
    update(2)  # warm-up
    return time_calls(lambda: update(1), steps)


def gradient_steps_per_env_step(config: dict, envs: int) -> float:
    """SB3's schedule: every train_freq vector steps, gradient_steps updates (-1: as many as env steps taken)."""
    grad = config["gradient_steps"]
    return 1.0 if grad < 0 else grad / (config["train_freq"] * envs)


def bench_learn(model, steps: int) -> float:
    """gw-train's loop for `steps` env steps after the warm buffer: env steps/s."""
    start = time.perf_counter()
    model.learn(total_timesteps=steps, progress_bar=False, reset_num_timesteps=False)
    return steps / (time.perf_counter() - start)


def bench_config(vec_env, config: dict, steps: int, vec: dict) -> dict:
    """One config: its gradient step, its replay costs, its loop measured and predicted from the parts."""
    torch.set_num_threads(config["torch_threads"] or DEFAULT_THREADS)
    torch.manual_seed(0)
    model = make_model(vec_env, config)
    warm_buffer(model, max(2 * config["batch_size"], 1000))
    replay = bench_replay(model, 200)
    grad_ms = bench_gradient(model, 30)
    per_env = gradient_steps_per_env_step(config, vec["envs"])
    predicted_ms = vec["vector_step_ms"] / vec["envs"] + per_env * (grad_ms + replay["sample_ms"])
    measured = bench_learn(model, steps)
    return {**config, "torch_threads_used": torch.get_num_threads(), "gradient_step_ms": grad_ms, **replay,
            "gradient_steps_per_env_step": per_env, "predicted_env_steps_per_s": 1e3 / predicted_ms,
            "measured_env_steps_per_s": measured,
            "share_of_time": {"simulation": (vec["vector_step_ms"] / vec["envs"]) / (1e3 / measured),
                              "learning": 1.0 - (vec["vector_step_ms"] / vec["envs"]) / (1e3 / measured)}}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--envs", type=int, default=2, help="parallel servers, as gw-train --envs")
    p.add_argument("--anatomies", default="train", help="the servers' anatomy set, as gw-train --anatomies")
    p.add_argument("--task", default="", help="task settings JSON (file or inline), as gw-train --task")
    p.add_argument("--steps", type=int, default=600, help="env steps timed per measurement")
    p.add_argument("--configs", default="shipped,fed", help="comma-separated configs (the docstring's names or "
                                                            "NAME=train_freq:gradient_steps:batch:net:threads)")
    p.add_argument("--out", default="", help="also write the JSON here")
    a = p.parse_args(argv)
    if a.envs < 1 or a.steps < 10:
        p.error("--envs must be >= 1 and --steps >= 10")
    configs = [parse_config(c) for c in a.configs.split(",") if c]
    settings = Settings(envs=a.envs, anatomies=a.anatomies, task=a.task, seed=0)

    report = {"commit": git_commit(), "machine": platform.machine(), "cores": torch.get_num_threads(),
              "torch": torch.__version__, "envs": a.envs, "steps": a.steps,
              "simulation": bench_simulation(settings, a.steps)}
    vec_envs = {a.envs: make_vec_env(settings)}  # one set of servers per number of servers the configs use
    report["vec_env"] = bench_vec_env(vec_envs[a.envs], a.steps)
    references = {a.envs: report["vec_env"]}
    report["configs"] = []
    for c in configs:
        envs = c["envs"] or a.envs
        if envs not in vec_envs:
            vec_envs[envs] = make_vec_env(dataclasses.replace(settings, envs=envs))
            references[envs] = bench_vec_env(vec_envs[envs], a.steps)
        report["configs"].append({**bench_config(vec_envs[envs], c, a.steps, references[envs]), "envs": envs,
                                  "vec_env": references[envs]})
    for vec_env in vec_envs.values():
        vec_env.close()
    text = json.dumps(report, indent=2)
    if a.out:
        Path(a.out).parent.mkdir(parents=True, exist_ok=True)
        Path(a.out).write_text(text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
