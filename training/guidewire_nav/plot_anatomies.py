"""Picture of the anatomy set: every anatomy's surface, centreline, inlet and numbered targets.

    python -m guidewire_nav.plot_anatomies [--index anatomies/index.json] [--out runs/anatomies.png]

Reads anatomies/index.json (written by `anatomy-gen --regenerate anatomies`), draws one 3D panel
per anatomy: the STL surface (translucent), the ground-truth centreline (grey), the inlet (blue,
with an arrow into the vessel) and the targets (green, numbered as in the truth JSON).
"""
from __future__ import annotations

import argparse
import json
import math
import struct
from pathlib import Path

import numpy as np

from guidewire_nav import REPO_ROOT


def read_binary_stl(path: Path) -> np.ndarray:
    """Triangles as an (n, 3, 3) float array (mm)."""
    data = path.read_bytes()
    (count,) = struct.unpack_from("<I", data, 80)
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    return np.frombuffer(data, dtype=record, count=count, offset=84)["v"].astype(np.float64)


def draw(ax, root: Path, entry: dict, max_faces: int = 12000) -> None:
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    tris = read_binary_stl(root / entry["mesh"])
    if len(tris) > max_faces:  # a fixed stride keeps the picture deterministic
        tris = tris[:: math.ceil(len(tris) / max_faces)]
    ax.add_collection3d(Poly3DCollection(tris, facecolor=(0.85, 0.3, 0.3, 0.10), edgecolor="none"))
    truth = json.loads((root / entry["truth"]).read_text())
    for b in truth["branches"]:
        p = np.asarray(b["points"])
        ax.plot(p[:, 0], p[:, 1], p[:, 2], color="0.3", lw=0.8)
    inlet = np.asarray(truth["inlet"]["position"])
    direction = np.asarray(truth["inlet"]["direction"])
    ax.scatter(*inlet, color="tab:blue", s=30, depthshade=False)
    ax.quiver(*inlet, *(direction * 10), color="tab:blue", lw=1.2)
    for t in truth["targets"]:
        q = np.asarray(t["position"])
        ax.scatter(*q, color="tab:green", s=22, depthshade=False)
        ax.text(q[0], q[1], q[2], f" {t['id']}", color="darkgreen", fontsize=8)
    for bif in truth["bifurcations"]:
        ax.scatter(*np.asarray(bif["position"]), color="black", s=6, depthshade=False)
    pts = tris.reshape(-1, 3)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)  # equal scale on every axis
    ax.set_title(f"{entry['set']}/{entry['name']}", fontsize=9)
    ax.tick_params(labelsize=6)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--index", help="anatomy index to draw (default: the repository's anatomies/index.json)")
    parser.add_argument("--out", default="runs/anatomies.png",
                        help="output PNG (default runs/anatomies.png; the committed picture is anatomies/anatomies.png)")
    args = parser.parse_args(argv)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    index = Path(args.index) if args.index else REPO_ROOT / "anatomies" / "index.json"
    if not index.is_file():
        parser.error(f"--index: {index}: no such anatomy index (give anatomies/index.json or a set's manifest)")
    root = index.resolve().parent.parent  # paths in the index are relative to the repository root
    entries = json.loads(index.read_text())["anatomies"]
    order = {"train": 0, "sensitivity": 1, "test": 2, "validation": 3}  # trained on, tested on, checkpoint choice
    entries.sort(key=lambda e: (order.get(e["set"], 3), e["name"]))
    cols = 4
    rows = math.ceil(len(entries) / cols)
    fig = plt.figure(figsize=(4.2 * cols, 4.0 * rows))
    for i, entry in enumerate(entries):
        draw(fig.add_subplot(rows, cols, i + 1, projection="3d"), root, entry)
    fig.suptitle("Anatomy set (mm): inlet blue, numbered targets green, bifurcation centres black", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.4 / fig.get_figheight()))  # leave the suptitle its own line
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(json.dumps({"out": args.out, "anatomies": len(entries)}))


if __name__ == "__main__":
    main()
