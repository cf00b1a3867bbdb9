"""What the controller saw and did during one navigate episode, step by step.

    python -m guidewire_nav.plot_episode OUT/episode3_target2.json [--out episode3.png]

Reads a trajectory JSON written by `navigate --out OUT` (schema guidewire-nav/trajectory/1 with
`frames.observation`) and draws, against the env step: omega (the tip bend against the wrong
branch; -1 = aimed away from it), lambda (distance to the current goal, normalised), the action,
and theta_1 (tip direction against the centreline ahead). Shaded spans are the steps the agent was
in control (near a bifurcation); dashed lines are hand-overs to the next goal. This is the picture
to look at when an episode ends in a wrong branch: was the tip aimed, and what did the policy do.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

SCHEMA = "guidewire-nav/trajectory/1"


def load_episode(path: Path) -> dict:
    """The trajectory's per-step columns; ValueError naming the file when it cannot be plotted."""
    try:
        trace = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise ValueError(f"{path}: cannot read a trajectory JSON ({e})") from e
    if not isinstance(trace, dict) or trace.get("schema") != SCHEMA:
        raise ValueError(f"{path}: not a navigate trajectory (schema {SCHEMA!r} expected)")
    frames = trace.get("frames", {})
    if "observation" not in frames or "observation_names" not in trace:
        raise ValueError(f"{path}: no per-step observations (written by a navigate older than 2026-11-28?)")
    names = list(trace["observation_names"])
    rows = frames["observation"]
    for k, row in enumerate(rows):
        if not isinstance(row, list) or len(row) != len(names):
            raise ValueError(f"{path}: observation {k} does not match the {len(names)} observation names")
    obs = np.asarray([[np.nan if v is None else v for v in row] for row in rows], dtype=float).reshape(-1, len(names))
    column = {name: obs[:, i] for i, name in enumerate(names)}
    for needed in ("omega", "lambda_t", "theta_t_1"):
        if needed not in column:
            raise ValueError(f"{path}: observation {needed!r} missing (names: {', '.join(names)})")
    return {
        "title": f"{trace['anatomy']} target {trace['target_id']}, seed {trace['seed']}, {trace['controller']}: "
                 f"{trace['outcome']}" + (f" ({trace['detail']})" if trace.get("detail") else "")
                 + (f", omega {trace['omega_at_loss']:+.2f} at the lost bifurcation"
                    if isinstance(trace.get("omega_at_loss"), (int, float)) else ""),
        "column": column,
        "action": np.asarray([np.nan if v is None else v for v in frames["action"]], dtype=float),
        "in_control": np.asarray(frames["agent_in_control"], dtype=bool),
        "goal": np.asarray(frames.get("goal", [0] * len(obs)), dtype=int),
    }


def control_spans(in_control: np.ndarray) -> list[tuple[int, int]]:
    """[start, end) step ranges where the agent was in control."""
    spans, start = [], None
    for k, on in enumerate(in_control):
        if on and start is None:
            start = k
        elif not on and start is not None:
            spans.append((start, k))
            start = None
    if start is not None:
        spans.append((start, len(in_control)))
    return spans


def plot(episode: dict, out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = episode["column"]
    steps = np.arange(len(episode["action"]))
    hand_overs = np.flatnonzero(np.diff(episode["goal"]) != 0) + 1
    fig, axes = plt.subplots(4, 1, figsize=(9, 8), sharex=True)
    rows = [("omega", c["omega"], (-1.05, 1.05)), ("lambda", c["lambda_t"], (0, None)),
            ("action", episode["action"], (-1.05, 1.05)), ("theta_1", c["theta_t_1"], (-1.05, 1.05))]
    for ax, (label, values, (low, high)) in zip(axes, rows):
        for a, b in control_spans(episode["in_control"]):
            ax.axvspan(a, b, color="tab:green", alpha=0.12, lw=0)
        for h in hand_overs:
            ax.axvline(h, color="0.4", ls="--", lw=0.8)
        ax.plot(steps, values, color="tab:blue", lw=1.2)
        if label == "omega" and "omega_side" in c:  # its sine (trajectories since 2026-11-30): which side
            ax.plot(steps, c["omega_side"], color="tab:orange", lw=0.9, label="omega_side")
            ax.legend(loc="upper right", fontsize=7)
        ax.axhline(0, color="0.7", lw=0.6)
        ax.set_ylabel(label)
        ax.set_ylim(low, high)
    axes[-1].set_xlabel("env step (shaded: agent in control; dashed: next goal)")
    fig.suptitle(episode["title"], fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trajectory", type=Path, help="episode<K>_target<T>.json from navigate --out")
    parser.add_argument("--out", type=Path, help="PNG to write (default: next to the trajectory, _steps.png)")
    args = parser.parse_args(argv)
    out = args.out or args.trajectory.with_name(args.trajectory.stem + "_steps.png")
    try:
        episode = load_episode(args.trajectory)
    except ValueError as e:
        print(f"plot_episode: {e}", file=sys.stderr)
        return 2
    plot(episode, out)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
