"""Average the weights of several exported actors into one (a "model soup", Wortsman et al. 2022).

    python -m guidewire_nav.average_actors out.json runs/a/scored/ckpt_final.json runs/b/scored/ckpt_40000.json

Why: fine-tunes of one base actor that differ only by seed land between 96 and 104 of 110 on the validation
trees (policy/trained/README.md); which seed is best is luck. Fine-tunes that start from the same weights
stay in one basin of the loss, so the mean of their weights is itself a good actor, and it keeps what
the runs agree on while their seed-specific drift partly cancels. Averaging actors trained from different
initialisations is meaningless (their hidden units are not aligned); this tool cannot tell and does not
try, so only average fine-tunes of one actor, or checkpoints of one run. Score a mean like any other actor
(score_checkpoints, all four validation trees): the first one tried gained on the coronary-like trees and
lost on the synthetic rows of the table (policy/trained/README.md), so it was not shipped.

Every input must compute the same kind of function: same format, observation layout and size, action
bounds, observation normalisation, layer shapes and activations. A mismatch is refused with the first
difference named, and nothing is written.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

import numpy as np

from guidewire_nav.export_actor import FORMAT, _git_commit


def _signature(d: dict) -> dict:
    """What must be equal for two actors' weights to be averaged (everything but the weights)."""
    return {
        "format": d.get("format"),
        "obs_layout": d.get("obs_layout"),
        "obs_size": d.get("obs_size"),
        "action_size": d.get("action_size"),
        "obs_normalization": d.get("obs_normalization"),
        "output": d.get("output"),
        "layers": [(layer["shape"], layer["activation"]) for layer in d.get("layers", [])],
    }


def average_actors(actors: list[dict], labels: list[str] | None = None) -> dict:
    """The actor whose every weight and bias is the mean of the inputs' (float64)."""
    labels = labels or [f"actor {i}" for i in range(len(actors))]
    if len(actors) < 2:
        raise ValueError("average_actors: need at least two actors")
    first = actors[0]
    if first.get("format") != FORMAT:
        raise ValueError(f"average_actors: {labels[0]}: format {first.get('format')!r}, expected {FORMAT!r}")
    want = _signature(first)
    for label, d in zip(labels[1:], actors[1:]):
        have = _signature(d)
        for key in want:
            if have[key] != want[key]:
                raise ValueError(f"average_actors: {label}: {key} {have[key]!r} differs from {labels[0]}'s {want[key]!r}")

    out = json.loads(json.dumps(first))  # deep copy of everything that is not a weight
    for i, layer in enumerate(out["layers"]):
        for key in ("weight", "bias"):
            stack = np.array([d["layers"][i][key] for d in actors], dtype=np.float64)
            if not np.all(np.isfinite(stack)):
                raise ValueError(f"average_actors: layer {i} {key} has a non-finite value")
            layer[key] = stack.mean(axis=0).tolist()
    out["git_commit"] = _git_commit()
    out["source"] = dict(first.get("source", {}), averaged_from=labels)
    return out


def _read(path: Path) -> tuple[dict, str]:
    """The actor in `path`, and its label: the path and a short content hash of the bytes parsed, so the
    soup's record names exactly which files went in."""
    data = path.read_bytes()
    return json.loads(data), f"{path} (sha256 {hashlib.sha256(data).hexdigest()[:12]})"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out", type=Path, help="averaged actor JSON to write")
    p.add_argument("actors", nargs="+", type=Path, help="exported actor JSONs (export_actor), at least two")
    a = p.parse_args(argv)
    try:
        actors, labels = zip(*(_read(path) for path in a.actors))
        soup = average_actors(list(actors), list(labels))
    except (OSError, ValueError, KeyError, TypeError) as e:  # json.JSONDecodeError is a ValueError
        print(f"error: {e}", file=sys.stderr)
        return 1
    a.out.write_text(json.dumps(soup, allow_nan=False))
    print(f"wrote {a.out}: mean of {len(actors)} actors")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
