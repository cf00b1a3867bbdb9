"""Success against env steps and against wall minutes for the runs of run.sh: summary.json and curves.png.

    python results/train_throughput/summarize.py --runs runs/train_throughput --out results/train_throughput

A checkpoint's wall time is read from the run's monitor CSV (SB3's `t`: seconds since the run started, at each
episode's end; the env steps are the episodes' lengths summed): the first episode end at or after the
checkpoint's step. Scores: scores_<run>.json (gw-score-checkpoints).
"""

from __future__ import annotations

import argparse
import csv
import json
from pathlib import Path

RUNS = ("shipped", "fed", "overlapped")


def monitor_clock(run: Path) -> list[tuple[int, float]]:
    """(env steps so far, seconds since the start) at every episode's end."""
    clock, steps = [], 0
    with open(run / "monitor.monitor.csv") as f:
        next(f)  # SB3's JSON header
        for row in csv.DictReader(f):
            steps += int(row["l"])
            clock.append((steps, float(row["t"])))
    return clock


def wall_at(clock: list[tuple[int, float]], step: int, final_wall: float) -> float:
    """Seconds since the start when the run had taken `step` env steps."""
    return next((t for s, t in clock if s >= step), final_wall)


def run_points(run: Path, scores: dict) -> dict:
    """One run: its settings, steps, wall time, throughput and a point per scored checkpoint."""
    summary = json.loads((run / "summary.json").read_text())
    clock = monitor_clock(run)
    points = []
    for label, score in scores["scores"].items():
        step = summary["steps"] if label == "final" else int(label)
        wall = summary["wall_time_s"] if label == "final" else wall_at(clock, step, summary["wall_time_s"])
        points.append({"checkpoint": label, "step": step, "wall_min": round(wall / 60, 2),
                       "validation": f"{score['validation_successes']}/{score['validation_episodes']}",
                       "validation_rate": score["validation_successes"] / score["validation_episodes"],
                       "training": f"{score['training_successes']}/{score['training_episodes']}"})
    s = summary["settings"]
    return {"command": summary["command"], "commit": summary["commit"],
            "schedule": {k: s[k] for k in ("train_freq", "gradient_steps", "batch_size", "net_arch", "envs")},
            "steps": summary["steps"], "wall_time_s": summary["wall_time_s"],
            "env_steps_per_s": round(summary["steps"] / summary["wall_time_s"], 1),
            "points": sorted(points, key=lambda p: p["step"])}


def plot(runs: dict, path: Path) -> None:
    """Two panels: validation success against env steps, and against wall minutes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for name, r in runs.items():
        xs = [p["step"] / 1000 for p in r["points"]], [p["wall_min"] for p in r["points"]]
        ys = [100 * p["validation_rate"] for p in r["points"]]
        label = f"{name} ({r['env_steps_per_s']} env steps/s)"
        for ax, x in zip(axes, xs):
            ax.plot(x, ys, "o-", label=label)
    axes[0].set_xlabel("env steps (thousands)")
    axes[1].set_xlabel("wall minutes (2 cores)")
    axes[0].set_ylabel("validation trees: success %")
    axes[0].legend()
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle("Validation success (150 episodes per checkpoint, seeds 1000+) by update schedule")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--runs", type=Path, default=Path("runs/train_throughput"), help="run.sh's run folders")
    p.add_argument("--out", type=Path, default=Path(__file__).resolve().parent, help="scores in, summary out")
    a = p.parse_args()
    runs = {name: run_points(a.runs / name, json.loads((a.out / f"scores_{name}.json").read_text()))
            for name in RUNS if (a.out / f"scores_{name}.json").exists()}  # the runs run.sh ran and scored
    bench = json.loads((a.out / "bench.json").read_text()) if (a.out / "bench.json").exists() else None
    (a.out / "summary.json").write_text(json.dumps({"bench": bench, "runs": runs}, indent=1) + "\n")
    plot(runs, a.out / "curves.png")
    for name, r in runs.items():
        print(f"{name}: {r['steps']} steps in {r['wall_time_s'] / 60:.1f} min ({r['env_steps_per_s']}/s); " +
              ", ".join(f"{p['checkpoint']}@{p['wall_min']}min {p['validation']}" for p in r["points"]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
