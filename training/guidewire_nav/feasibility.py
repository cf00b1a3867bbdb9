"""Can a target be reached by rotation alone? Tries a family of open- and closed-loop rotation schedules.

A learned policy can only be as good as the best rotation-only controller: the task pushes the wire at a
constant speed and the action is the proximal rotation rate. When no schedule of a varied family reaches
a target from any start orientation, the failure is the wire and the anatomy (e.g. a side branch on the
inner side of a bend, beyond the tip's lateral reach), not the controller. The results table cites this.

    python -m guidewire_nav.feasibility --cases t3_out_of_plane_steep:1,t1_straight_y:2 --seeds 4
    python -m guidewire_nav.feasibility --cases coronary:1 --anatomies test --out results/feasibility.json

Schedules (omega = observation 9; +1 = tip bent towards the wrong branch):
  aim-0.95 / aim-0.7   turn at full rate while omega > threshold, then hold (the scripted baseline
                       of `navigate`/`evaluate` is aim-0.95); aim-0.95-ccw the same turning the other way
  spin+-0.3, spin+-1   constant rotation rate (fraction of one turn per second)
  wiggle               a = sin(0.3 k), sweeping back and forth
A case counts as reachable when any schedule reaches it from any of the seeds.

The C++ side has the same family (lib/runner/rotation_schedules.hpp): `evaluate` probes the targets
no controller of a row reached with it, and `navigate --controller spin+1` runs one. Keep the two in step:
tests/python/test_feasibility.py replays a C++ episode of each schedule through the rule here.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from guidewire_nav.baselines import SCRIPTED_OMEGA_RELEASE, scripted_omega_action  # the scripted rule

# schedule(omega, k): the action from omega (read at the index the server's spec names) and k, the number of
# actions the task has applied so far (steps in control: on trees only near a bifurcation), as the C++
# schedules count them.
SCHEDULES = {
    "aim-0.95": lambda omega, k: scripted_omega_action(omega, SCRIPTED_OMEGA_RELEASE, 1.0),
    "aim-0.7": lambda omega, k: scripted_omega_action(omega, -0.7, 1.0),
    "aim-0.95-ccw": lambda omega, k: scripted_omega_action(omega, SCRIPTED_OMEGA_RELEASE, -1.0),
    "spin-1": lambda omega, k: -1.0,
    "spin-0.3": lambda omega, k: -0.3,
    "spin+0.3": lambda omega, k: 0.3,
    "spin+1": lambda omega, k: 1.0,
    "wiggle": lambda omega, k: math.sin(0.3 * k),
}


def run_episode(env, anatomy: str, target: int, seed: int, schedule) -> bool:
    """One seeded episode under `schedule`; whether it reached the target."""
    obs, info = env.reset(seed=seed, options={"anatomy": anatomy, "target": target})
    k, done = 0, False
    while not done:
        applied = bool(info.get("in_control", True))  # the task applies the next action (else it is ignored)
        action = schedule(float(obs[env.omega_index]), k) if applied else 0.0
        obs, _, terminated, truncated, info = env.step(np.array([action], dtype=np.float32))
        k += applied
        done = terminated or truncated
    return bool(info["success"])


def probe(anatomy: str, target: int, seeds: int, schedules: list[str], anatomies: str) -> dict:
    from guidewire_nav.env import GuidewireEnv

    env = GuidewireEnv(anatomies=anatomies)
    try:
        successes = {}
        for name in schedules:
            successes[name] = sum(run_episode(env, anatomy, target, seed, SCHEDULES[name]) for seed in range(seeds))
    finally:
        env.close()
    return {"anatomy": anatomy, "target": target, "seeds": seeds, "successes": successes,
            "reachable": any(v > 0 for v in successes.values())}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cases", required=True, help="comma-separated anatomy:target, e.g. t3_out_of_plane_steep:1")
    p.add_argument("--anatomies", default="", help="anatomy set the server loads (default: the cases' anatomies)")
    p.add_argument("--seeds", type=int, default=4, help="start orientations per schedule (seeds 0..N-1)")
    p.add_argument("--schedules", default=",".join(SCHEDULES), help="comma-separated subset of the schedules")
    p.add_argument("--out", help="write the results as JSON here")
    a = p.parse_args(argv)

    schedules = a.schedules.split(",")
    unknown = [s for s in schedules if s not in SCHEDULES]
    if unknown:
        p.error(f"unknown schedules {unknown}; known: {', '.join(SCHEDULES)}")
    cases = []
    for item in a.cases.split(","):
        name, _, target = item.rpartition(":")
        if not name or not target.isdigit():
            p.error(f"case '{item}' is not anatomy:target")
        cases.append((name, int(target)))

    results = []
    for name, target in cases:
        r = probe(name, target, a.seeds, schedules, a.anatomies or name)
        results.append(r)
        verdict = "reachable" if r["reachable"] else "NOT reached by any schedule"
        print(f"{name} T{target}: {verdict}  {r['successes']}", file=sys.stderr, flush=True)
    report = {"seeds": a.seeds, "schedules": schedules, "cases": results}
    if a.out:
        Path(a.out).write_text(json.dumps(report, indent=2) + "\n")
    print(json.dumps(report))
    return 0


if __name__ == "__main__":
    sys.exit(main())
