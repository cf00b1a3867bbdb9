"""Demonstrations from the procedure planner over an anatomy pool (issue 64: the generalist's data set).

For every anatomy of a pool (gw-anatomy-pool's index.json) and every target of it (as navigate numbers them), one
episode with its own seed (its start orientation) is planned by `plan` (docs/planning.md) and the plan's steps are
kept as (observation, action) pairs in the planning task's layouts (obs/8, act/2), one JSON line per step:
  OUT/episodes/<anatomy>_t<T>_s<S>.jsonl   the plan's pairs (absent when no plan was found)
  OUT/plans.jsonl                           one line per episode planned: what was found, its steps, forces, time
  OUT/settings.jsonl                        one line per call: its arguments and the commit it ran on
The episodes run in a seeded shuffled order, so that a data set cut short is a uniform sample of the pool; an
episode already in plans.jsonl is not planned again (a run resumes where it stopped). Bounded by --max-minutes
and --max-episodes.
  gw-plan-demos --anatomies runs/pool/train/index.json --out runs/demos --jobs 2
"""
from __future__ import annotations

import argparse
import json
import random
import re
import subprocess
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from guidewire_nav import app_path
from guidewire_nav.export_actor import _git_commit

TARGET_LINE = re.compile(r"^\s+(\d+)\s+\(")


def parse_args(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--anatomies", required=True, help="a pool's index.json (gw-anatomy-pool)")
    p.add_argument("--out", required=True, help="directory for episodes/ and plans.jsonl")
    p.add_argument("--seed", type=int, default=1, help="the episodes' order and their start seeds")
    p.add_argument("--jobs", type=int, default=2, help="plans run at once (one core each)")
    p.add_argument("--budget", type=int, default=10000, help="plan --budget: env steps one search may simulate")
    p.add_argument("--max-episodes", type=int, default=0, help="plan at most this many episodes (0: all)")
    p.add_argument("--max-minutes", type=float, default=0.0, help="start no plan after this many minutes (0: none)")
    p.add_argument("--lead-in", default="", help="an actor JSON: plan each episode from where it stopped getting "
                   "deeper (plan --lead-in); the demonstrations are the search's steps only")
    return p.parse_args(argv)


def targets_of(navigate: str, mesh: Path) -> list[int]:
    """The target numbers navigate gives the anatomy (its --list)."""
    r = subprocess.run([navigate, "--anatomy", str(mesh), "--list"], capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        raise RuntimeError(f"{mesh}: navigate --list failed: {r.stderr.strip()[-300:]}")
    return [int(m.group(1)) for line in r.stdout.splitlines() if (m := TARGET_LINE.match(line))]


def episodes_of(index_path: Path, navigate: str, seed: int) -> list[dict]:
    """Every (anatomy, target) of the pool with its own start seed, in a seeded shuffled order."""
    index = json.loads(index_path.read_text())
    rng = random.Random(seed)
    episodes = []
    for a in index["anatomies"]:
        mesh = index_path.parent.parent / a["mesh"]  # the index names its meshes from the pool's parent folder
        for t in targets_of(navigate, mesh):
            episodes.append({"anatomy": a["name"], "mesh": str(mesh), "target": t, "seed": rng.randrange(1 << 31)})
    rng.shuffle(episodes)
    return episodes


def plan_one(plan_bin: str, e: dict, out: Path, budget: int, lead_in: str) -> dict:
    """Plan one episode; its demonstrations into out/episodes; returns its plans.jsonl line."""
    name = f"{e['anatomy']}_t{e['target']}_s{e['seed']}"
    demos = out / "episodes" / f"{name}.jsonl"
    start = time.time()
    r = subprocess.run([plan_bin, "--anatomy", e["mesh"], "--target", str(e["target"]), "--seed", str(e["seed"]),
                        "--budget", str(budget), "--demos", str(demos), "--json"]
                       + (["--lead-in", lead_in] if lead_in else []),
                       capture_output=True, text=True, timeout=3600)
    line = {**{k: e[k] for k in ("anatomy", "target", "seed")}, "seconds": round(time.time() - start, 2)}
    if r.returncode not in (0, 2):
        return {**line, "found": "error", "why": r.stderr.strip()[-300:]}
    plan = json.loads(r.stdout)
    if not plan["reached"]:
        demos.unlink(missing_ok=True)  # no plan: no demonstration
    return {**line, "found": plan["found"], "steps": plan.get("steps"), "wrong_entries": plan.get("wrong_entries"),
            "peak_tip_force_N": plan.get("peak_tip_force_N"), "peak_node_force_N": plan.get("peak_node_force_N"),
            "demos": demos.name if plan["reached"] else None,
            **({"lead_in": plan["lead_in"]} if "lead_in" in plan else {})}


def main(argv=None) -> int:
    args = parse_args(argv)
    out = Path(args.out)
    (out / "episodes").mkdir(parents=True, exist_ok=True)
    with (out / "settings.jsonl").open("a") as f:  # one line per call: what each part of the data set was made with
        f.write(json.dumps({**vars(args), "git_commit": _git_commit(), "started": time.strftime("%Y-%m-%dT%H:%M:%S")}) + "\n")
    episodes = episodes_of(Path(args.anatomies), str(app_path("navigate")), args.seed)
    log = out / "plans.jsonl"
    done = {(d["anatomy"], d["target"], d["seed"]) for d in map(json.loads, log.read_text().splitlines())} \
        if log.is_file() else set()
    todo = [e for e in episodes if (e["anatomy"], e["target"], e["seed"]) not in done]
    if args.max_episodes:
        todo = todo[:max(0, args.max_episodes - len(done))]
    print(f"plan_demos: {len(episodes)} episodes in the pool, {len(done)} planned before, {len(todo)} to plan")
    deadline = time.time() + 60 * args.max_minutes if args.max_minutes else float("inf")
    lock = threading.Lock()

    def work(e: dict) -> None:
        if time.time() > deadline:
            return
        line = plan_one(str(app_path("plan")), e, out, args.budget, args.lead_in)
        with lock, log.open("a") as f:
            f.write(json.dumps(line) + "\n")

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        list(pool.map(work, todo))
    lines = [json.loads(x) for x in log.read_text().splitlines()]
    found = {k: sum(d["found"] == k for d in lines) for k in ("strict", "procedure", "none", "error")}
    print(json.dumps({"episodes": len(lines), "found": found,
                      "pairs": sum(d.get("steps") or 0 for d in lines if d.get("demos"))}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
