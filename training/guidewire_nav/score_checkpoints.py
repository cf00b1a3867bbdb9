"""Score a training run's checkpoints zero-shot: the validation trees and the training anatomies.

Checkpoints of one SAC run that are equal on the training anatomies (35-37 of 40) have ranged from 18 to
98 of 110 episodes on the three coronary-like validation trees (policy/trained/README.md): the training
objective does not hold a policy's behaviour on trees in place, so a run is judged, and a checkpoint
picked, on anatomies it never saw. A fourth tree, syn_validation (constant radius, the synthetic rows'
bifurcation shapes), catches what the coronary-like ones miss: 150 episodes in all at 10 per target. The
validation trees (anatomies/validation) are in no row of the results table, and the seeds (1000+ on the
trees, 5000+ on the training anatomies) are apart from the table's (0+).

    python -m guidewire_nav.score_checkpoints runs/sac --steps 50000,60000,final
    python -m guidewire_nav.score_checkpoints --actors policy/trained/sac_actor.json ckpt.json --json

Each actor runs through the C++ runtime (`navigate --json` per validation target, `evaluate` on the
training anatomies), as `navigate` would run it for a user. Checkpoints are exported next to the run
(`<run>/scored/ckpt_<step>.json`) with the run's observation layout.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import guidewire_nav

# (mesh, targets): every target some controller reaches (pl_validation T1 and T5 are out of the tip's reach).
# The three coronary-like trees alone missed a regression on the synthetic rows' bifurcation shapes (a
# weight-averaged actor: +8 of 220 there, -5 of 89 reachable training episodes); syn_validation has those
# shapes (anatomies/validation/syn_validation/make_spec.py) and scored that actor 25 of 40 against 38.
VALIDATION = [
    ("anatomies/validation/rca_validation/rca_validation.stl", [1, 2, 3, 4]),
    ("anatomies/validation/rca_validation_deformed/rca_validation_deformed.stl", [1, 2, 3, 4]),
    ("anatomies/validation/pl_validation/pl_validation.stl", [2, 3, 4]),
    ("anatomies/validation/syn_validation/syn_validation.stl", [1, 2, 3, 4]),
]
def legacy_observation(settings: dict) -> dict:
    """The task JSON of a run's settings.json written before --task: its observation flags (omega_plane,
    omega_side, junctions, push_pull, since_progress) as the task's observation object."""
    observation = {"omega_plane": settings.get("omega_plane", "approach"),
                   "omega_side": bool(settings.get("omega_side", False)),
                   "junctions": settings.get("junctions", "separate"),
                   "push_pull": bool(settings.get("push_pull", False))}
    if settings.get("since_progress") or (observation["omega_plane"] == "approach" and not observation["omega_side"]):
        raise SystemExit("the run trained a retired observation layout (obs/2 or obs/7, docs/policy_history.md "
                         "\"Retired settings\"): score it with the commit named there")
    task = {"observation": observation}
    if observation["push_pull"]:
        task["action"] = "guidewire-nav/act/2"
    return task


def run_layout(settings: dict) -> str:
    """The observation layout a run's settings.json trained on: what a server started with the run's task
    settings says in its spec (the C++ ObservationLayout; no copy of the layouts here)."""
    from guidewire_nav.env import GuidewireEnv
    from guidewire_nav.train import Settings, server_args

    known = {f.name for f in dataclasses.fields(Settings)}
    run = Settings(**{k: v for k, v in settings.items() if k in known})
    if "task" not in settings:  # a run before the task JSON (2026-12-04): its flags chose the observation
        run.task = json.dumps(legacy_observation(settings))
    env = GuidewireEnv(anatomies="t1_straight_y", server_args=server_args(run))
    try:
        return env.spec_reply["obs_layout"]
    finally:
        env.close()


def app(name: str) -> Path:
    """A C++ executable from the build folder ($GW_BUILD_DIR, default <repo>/build)."""
    path = guidewire_nav.app_path(name)
    if not path.exists():
        raise FileNotFoundError(f"{path}: not built (cmake --build build), or set GW_BUILD_DIR")
    return path


def run(cmd: list[str]) -> str:
    """stdout of `cmd` run from the repository root; a failure raises with what the command said."""
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=guidewire_nav.REPO_ROOT)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {out.stderr.strip() or out.stdout.strip()}")
    return out.stdout


# --- The actors to score -------------------------------------------------------------------------------------


def export_checkpoints(run: Path, steps: list[str]) -> dict[str, Path]:
    """Exports <run>/checkpoints/sac_<N>_steps.zip ('final': final_model.zip) with the run's obs layout."""
    from stable_baselines3 import SAC

    from guidewire_nav.export_actor import export_sac_actor

    settings = json.loads((run / "settings.json").read_text()) if (run / "settings.json").exists() else {}
    layout = run_layout(settings)
    (run / "scored").mkdir(exist_ok=True)
    actors = {}
    for step in steps:
        zip_path = run / "final_model.zip" if step == "final" else run / "checkpoints" / f"sac_{step}_steps.zip"
        if not zip_path.exists():
            raise FileNotFoundError(f"{zip_path}: no such checkpoint in {run}")
        out = run / "scored" / f"ckpt_{step}.json"
        export_sac_actor(SAC.load(zip_path, device="cpu"), out, obs_layout=layout)
        actors[step] = out
    return actors


# --- Scoring -------------------------------------------------------------------------------------------------


def score_validation(actor: Path, episodes: int, seed: int, threads: int) -> dict[str, dict[int, int]]:
    """Successes per validation anatomy and target, `episodes` seeded episodes each."""
    scores: dict[str, dict[int, int]] = {}
    for mesh, targets in VALIDATION:
        name = Path(mesh).stem
        for target in targets:
            summary = json.loads(run([str(app("navigate")), "--anatomy", mesh, "--target", str(target), "--policy",
                                str(actor), "--episodes", str(episodes), "--seed", str(seed), "--threads",
                                str(threads), "--json"]))
            scores.setdefault(name, {})[target] = int(summary["outcomes"]["success"])
    return scores


def score_training(actor: Path, episode_scale: float, seed: int, threads: int) -> tuple[int, int]:
    """(successes, episodes) on the training anatomies' row of `evaluate`."""
    with tempfile.TemporaryDirectory() as tmp:
        run([str(app("evaluate")), "--rows", "training anatomies", "--controllers", "policy", "--policy", str(actor),
             "--episode-scale", str(episode_scale), "--seed", str(seed), "--threads", str(threads),
             "--reachability-seeds", "0", "--out", tmp])
        row = json.loads((Path(tmp) / "results.json").read_text())["rows"][0]
    if "skipped" in row:
        raise RuntimeError(f"evaluate skipped the training row: {row['skipped']}")
    summary = row["results"]["sac-policy"]
    return int(summary["outcomes"]["success"]), int(summary["episodes"])


def markdown(scores: dict[str, dict]) -> str:
    names = [Path(m).stem for m, _ in VALIDATION]
    lines = ["| actor | " + " | ".join(names) + " | validation total | training anatomies |",
             "|---" * (len(names) + 3) + "|"]
    for label, s in scores.items():
        per = [f"{sum(s['validation'][n].values())}/{len(s['validation'][n]) * s['episodes_per_target']}"
               for n in names]
        lines.append(f"| {label} | " + " | ".join(per) +
                     f" | **{s['validation_successes']}/{s['validation_episodes']}** | "
                     f"{s['training_successes']}/{s['training_episodes']} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run", nargs="?", type=Path, help="training run folder (train.py --out)")
    p.add_argument("--steps", default="final", help="comma-separated checkpoint steps, 'final' = final_model.zip")
    p.add_argument("--actors", nargs="+", type=Path, default=[], help="exported actor JSONs to score as well")
    p.add_argument("--episodes", type=int, default=10, help="episodes per validation target")
    p.add_argument("--seed", type=int, default=1000, help="validation seeds S.. (the table uses 0..)")
    p.add_argument("--train-episode-scale", type=float, default=0.4,
                   help="training anatomies: this times the table's 100 episodes (0 = skip)")
    p.add_argument("--train-seed", type=int, default=5000, help="training anatomies: seeds S..")
    p.add_argument("--threads", type=int, default=os.cpu_count() or 1, help="episodes run in parallel")
    p.add_argument("--out", type=Path, help="write the scores as JSON here (default: <run>/scores.json)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a Markdown table")
    a = p.parse_args(argv)
    if a.run is None and not a.actors:
        p.error("give a run folder, --actors, or both")
    if a.episodes < 1:
        p.error("--episodes must be at least 1")

    try:
        actors = {str(path): path for path in a.actors}
        if a.run is not None:
            actors.update(export_checkpoints(a.run, [s.strip() for s in a.steps.split(",") if s.strip()]))
        scores = {}
        for label, actor in actors.items():
            validation = score_validation(actor, a.episodes, a.seed, a.threads)
            trained = score_training(actor, a.train_episode_scale, a.train_seed, a.threads) \
                if a.train_episode_scale > 0 else (0, 0)
            scores[label] = {
                "actor": str(actor), "episodes_per_target": a.episodes, "validation": validation,
                "validation_successes": sum(sum(t.values()) for t in validation.values()),
                "validation_episodes": a.episodes * sum(len(t) for _, t in VALIDATION),
                "training_successes": trained[0], "training_episodes": trained[1]}
            print(f"[score] {label}: {scores[label]['validation_successes']}/{scores[label]['validation_episodes']} "
                  f"validation, {trained[0]}/{trained[1]} training", file=sys.stderr)
    except (FileNotFoundError, RuntimeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1

    report = {"seed": a.seed, "train_seed": a.train_seed, "scores": scores}
    out = a.out or (a.run / "scores.json" if a.run is not None else None)
    if out is not None:
        out.write_text(json.dumps(report, indent=1))
    print(json.dumps(report, indent=1) if a.json else markdown(scores))
    return 0


if __name__ == "__main__":
    sys.exit(main())
