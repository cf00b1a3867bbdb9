"""Lower anchors for RL on the navigation task: push-only and a scripted omega controller (both turn directions).

    python -m guidewire_nav.baselines --episodes 20 --workers 2      # prints one JSON object

Both run through GuidewireEnv (one local server per worker), on the training anatomies by default,
targets and start poses drawn from the episode seeds, so the numbers are reproducible.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
from collections import defaultdict

import numpy as np

from guidewire_nav.env import GuidewireEnv

# The scripted omega rule, the one Python implementation (C++: scripted_omega_action, lib/runner/controller.hpp,
# the same threshold): turn at full rate while the tip bends less than 18 degrees short of straight away from the
# wrong branch (omega > release), then hold. Used by OmegaController and the aim-* schedules of feasibility.py.
SCRIPTED_OMEGA_RELEASE = -0.95


def scripted_omega_action(omega: float, release: float = SCRIPTED_OMEGA_RELEASE, turn: float = 1.0) -> float:
    """The rotation action of the scripted omega rule: `turn` (+1 or -1) while omega > release, else 0."""
    return turn if float(omega) > release else 0.0


class PushOnly:
    """Never rotates: whatever the random start roll gives."""

    name = "push_only"

    def __init__(self, omega_index: int = 0):
        pass

    def reset(self) -> None:
        pass

    def __call__(self, obs: np.ndarray) -> float:
        return 0.0


class OmegaController:
    """Turns at full rate until the tip bends away from the wrong branch, then holds.

    omega = k_p . w_p is +1 when the tip bends towards the wrong branch and -1 when it bends away.
    Turning one way at a constant rate sweeps the bend round until omega drops to `release`. The same
    rule as the C++ `scripted-omega` controller of navigate and evaluate (lib/runner/controller.cpp),
    so a number from here and one from the results table mean the same baseline. omega has no side, so
    the rule turns one fixed way; `OmegaControllerCCW` is the C++ `scripted-omega-ccw`, turning the other."""

    name = "omega_scripted"
    turn = 1.0

    def __init__(self, omega_index: int, release: float = SCRIPTED_OMEGA_RELEASE):
        self.omega_index, self.release = omega_index, release  # omega's index: env.omega_index (the spec's names)

    def reset(self) -> None:
        pass

    def __call__(self, obs: np.ndarray) -> float:
        return scripted_omega_action(obs[self.omega_index], self.release, self.turn)


class OmegaControllerCCW(OmegaController):
    """The scripted rule mirrored: where it stops (short of -1, on the side it came from) can decide a fork."""

    name = "omega_scripted_ccw"
    turn = -1.0


CONTROLLERS = {"push_only": PushOnly, "omega_scripted": OmegaController, "omega_scripted_ccw": OmegaControllerCCW}


def run_episodes(controller_name: str, anatomy: str, seeds: list[int], env_kwargs: dict) -> list[dict]:
    """Runs one episode per seed on `anatomy`; returns the final info of each (plus return and steps)."""
    env = GuidewireEnv(**env_kwargs)
    controller = CONTROLLERS[controller_name](env.omega_index)
    results = []
    try:
        for seed in seeds:
            obs, info = env.reset(seed=seed, options={"anatomy": anatomy})
            controller.reset()
            total, steps, done = 0.0, 0, False
            while not done:
                obs, reward, terminated, truncated, info = env.step(np.array([controller(obs)], dtype=np.float32))
                total += reward
                steps += 1
                done = terminated or truncated
            results.append(
                {
                    "anatomy": anatomy,
                    "target": info["target"],
                    "seed": seed,
                    "success": bool(info["success"]),
                    "wrong_branch": bool(info["wrong_branch"]),
                    "stuck": bool(info["stuck"]),
                    "step_limit": bool(info["step_limit"]),
                    "problem": info.get("problem", ""),
                    "steps": steps,
                    "return": total,
                }
            )
    finally:
        env.close()
    return results


def _job(args):
    return run_episodes(*args)


def evaluate(controllers, anatomies, episodes: int, seed: int, workers: int, env_kwargs: dict) -> dict:
    unknown = [c for c in controllers if c not in CONTROLLERS]
    if unknown:
        raise ValueError(f"unknown controller {unknown[0]!r} (known: {', '.join(CONTROLLERS)})")
    jobs = [
        (c, a, [seed + 1000 * i + k for k in range(episodes)], env_kwargs)
        for c in controllers
        for i, a in enumerate(anatomies)
    ]
    if workers > 1:
        with mp.get_context("spawn").Pool(workers) as pool:
            chunks = pool.map(_job, jobs)
    else:
        chunks = [_job(j) for j in jobs]
    summary: dict = {"episodes_per_anatomy": episodes, "seed": seed, "controllers": {}}
    for (c, a, _, _), results in zip(jobs, chunks):
        entry = summary["controllers"].setdefault(c, {"per_anatomy": {}, "episodes": 0, "successes": 0})
        counts = defaultdict(int)
        for r in results:
            counts["successes"] += r["success"]
            counts["wrong_branch"] += r["wrong_branch"]
            counts["stuck"] += r["stuck"]
            counts["step_limit"] += r["step_limit"]
            counts["physics_problem"] += bool(r["problem"])
        entry["per_anatomy"][a] = {
            "episodes": len(results),
            "success_rate": counts["successes"] / len(results),
            **dict(counts),
            "mean_return": float(np.mean([r["return"] for r in results])),
            "mean_steps": float(np.mean([r["steps"] for r in results])),
        }
        entry["episodes"] += len(results)
        entry["successes"] += counts["successes"]
    for entry in summary["controllers"].values():
        entry["success_rate"] = entry["successes"] / max(1, entry["episodes"])
    return summary


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--anatomies", default="t1_straight_y,t2_curved_straight_exit,t3_out_of_plane_steep,t4_s_curving_back",
                   help="comma-separated anatomy names")
    p.add_argument("--controllers", default="push_only,omega_scripted,omega_scripted_ccw",
                   help="comma-separated: " + ", ".join(CONTROLLERS))
    p.add_argument("--episodes", type=int, default=20, help="episodes per anatomy and controller")
    p.add_argument("--seed", type=int, default=0, help="first episode seed (anatomy i, episode k: S + 1000 i + k)")
    p.add_argument("--workers", type=int, default=2, help="parallel processes, one server each")
    p.add_argument("--host", default=None, help="use a running server instead of starting one per worker")
    p.add_argument("--port", type=int, default=None, help="port of the running server (with --host)")
    args = p.parse_args()
    anatomies = [a for a in args.anatomies.split(",") if a]
    env_kwargs = {"anatomies": ",".join(anatomies)} if args.port is None else {"host": args.host, "port": args.port}
    summary = evaluate(args.controllers.split(","), anatomies, args.episodes, args.seed, args.workers, env_kwargs)
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
