"""gw-anatomy-pool: a seeded pool of generated anatomies, the training and validation distribution of issue 64.

    gw-anatomy-pool --out runs/pool/train --count 200 --seed 1          # specs, meshes, truth, index.json
    gw-anatomy-pool --out runs/pool/validation --count 40 --seed 900001 # held apart: other seeds
    guidewire-server --anatomies runs/pool/train/index.json             # every anatomy of the pool

Inputs: a seed, a count, the kinds to draw (coronary trees, aortic arches). Outputs: OUT/<kind>/<name>/<name>.
{spec.json,stl,truth.json} and OUT/index.json (the anatomies/index.json format, paths relative to OUT's parent).
Sample i of seed S is drawn from numpy's Generator seeded with (S, i), so a pool grows or resumes (meshes already
written are kept) and the same seed gives the same specs. What is drawn (docs/anatomy_pool.md):
- coronary trees on an ellipsoidal heart (semi-axes 30-40, 30-40, 45-55 mm): a main stem ending in a two-way
  fork or a trifurcation, children with side branches on either side, close pairs of side branches 5 mm apart,
  geodesic curvature on either side (so side branches leave on the inner side of a turn as well as the outer),
  radii tapering from 1.6-2.2 mm to distal ends of 0.3-0.9 mm, and a cardiac deformation at a random phase in
  three of ten;
- aortic arches of Types I-III (anatomies/segmentation/make_arch_specs.py's construction with a random height and
  great-vessel angles), entered from the descending aorta, with the 0.035" aortic wire (its JSON copied to
  OUT/wires/ and named by each arch's index entry: one server serves a mixed pool, each anatomy with its wire).
A drawn tree whose branches come closer than their radii plus 0.6 mm (away from their junction) is drawn again,
and so is one that anatomy-gen refuses (redraw k of sample i from (S, i, k), named as before; --specs-only writes
first draws, unchecked). An anatomy already meshed keeps its spec.
"""

import argparse
import functools
import importlib.util
import json
import math
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from guidewire_nav import app_path
from guidewire_nav.heart_walk import STEP_MM, on_surface, rotate, spec_branch, surface_normal, taper, walk

REPO = Path(__file__).resolve().parents[2]
KINDS = ("coronary", "arch")
KIND_WIRES = {"arch": "aortic_035_angled.json"}  # the wire a kind is navigated with, when not the run's (engine/wire/)
BASE_WIRES = {"coronary": "coronary_014.json", **KIND_WIRES}  # --vary-wires: each kind's wire before the draw
# --vary-wires: what a clinician changes from case to case on the same wire model, drawn per anatomy. Tip: shaped
# by hand, 3-9 mm bent 40-100 degrees on a coronary wire (the shipped one: 6 mm, 69), 6-14 mm bent 30-60 degrees
# on the angled aortic wire (10 mm, 45); the bent length stays within the wire's fine tip elements. Friction:
# 0.05-0.15 on the coronary wire (0.1), 0.03-0.08 on the hydrophilic aortic one (0.05). Assumed ranges, not
# measured (docs/anatomy_pool.md).
WIRE_RANGES = {"coronary": {"tip_length_mm": (3, 9), "tip_bend_deg": (40, 100), "friction": (0.05, 0.15)},
               "arch": {"tip_length_mm": (6, 14), "tip_bend_deg": (30, 60), "friction": (0.03, 0.08)}}
WIRE_STREAM = 7  # the wire of sample i of seed S is drawn from (S, i, WIRE_STREAM, 0): apart from its spec's draws
BEAT_STREAM = 8  # --beating: its heart from (S, i, BEAT_STREAM, 0)
MAX_HEART_RATE_BPM = 120
MAX_TARGETS = 8
MAX_REDRAWS = 5  # draws of one sample after anatomy-gen refused its spec


def child_branch(branches, parent, at, angle_deg, length_mm, curvature, r0, r1, axes, name):
    """A branch leaving `parent` at its point `at`, turned angle_deg about the surface normal."""
    p = branches[parent]["points"][at]
    d = rotate(branches[parent]["directions"][at], surface_normal(p, axes), math.radians(angle_deg))
    points, directions = walk(p, d, length_mm, curvature, axes)
    return dict(name=name, parent=parent, at=at, points=points, directions=directions,
                radius=taper(len(points), r0, r1))


def junction_children(rng, kind):
    """Take-off angles (deg) of a fork's children: two-way or trifurcation."""
    if kind == "trifurcation":
        return [rng.uniform(25, 45), rng.uniform(-10, 10), -rng.uniform(25, 45)]
    return [rng.uniform(15, 55), -rng.uniform(15, 55)]


def side_branches(rng, branches, b, axes, distal):
    """Side branches along branch b: none, one on either side, or a close pair 5 mm apart on opposite sides."""
    n = len(branches[b]["points"])
    if n < 7 or rng.random() < 0.3:
        return
    at = int(rng.integers(2, n - 3))
    side = 1 if rng.random() < 0.5 else -1
    pair = rng.random() < 0.3
    for k, s in enumerate([side, -side] if pair else [side]):
        r0 = round(branches[b]["radius"][at + k] * rng.uniform(0.6, 0.85), 3)
        branches.append(child_branch(branches, b, at + k, s * rng.uniform(25, 70), 5 * rng.integers(5, 10),
                                     rng.uniform(-0.01, 0.01), r0, distal(r0), axes, f"S{len(branches)}"))


def sample_coronary_branches(rng, axes):
    """Branch dicts of one coronary tree: a stem, a fork, children with side branches, maybe a second fork."""
    u, v = rng.uniform(0, 2 * math.pi), math.radians(rng.uniform(28, 48))
    start = on_surface(np.array([axes[0] * math.cos(v) * math.cos(u), axes[1] * math.cos(v) * math.sin(u),
                                 axes[2] * math.sin(v)]), axes)
    n0 = surface_normal(start, axes)
    down = np.array([0.0, 0.0, -1.0]) + n0 * n0[2]  # straight down, projected on the tangent plane
    heading = rotate(down / np.linalg.norm(down), n0, math.radians(rng.uniform(-50, 50)))
    r_stem = round(rng.uniform(1.6, 2.2), 3)
    points, directions = walk(start, heading, 5 * rng.integers(2, 5), 0.0, axes)
    branches = [dict(name="stem", parent=None, at=None, points=points, directions=directions,
                     radius=[r_stem] * len(points))]

    def distal(r0):  # the distal radius: 0.3-0.9 mm, narrower than the branch's start
        return round(min(rng.uniform(0.3, 0.9), 0.9 * r0), 3)

    fork = "trifurcation" if rng.random() < 0.3 else "two-way"
    for angle in junction_children(rng, fork):
        r0 = round(r_stem * rng.uniform(0.7, 0.92), 3)
        branches.append(child_branch(branches, 0, len(points) - 1, angle, 5 * rng.integers(9, 17),
                                     rng.uniform(-0.01, 0.01), r0, distal(r0), axes, f"B{len(branches)}"))
    main_children = list(range(1, len(branches)))
    for b in main_children:
        side_branches(rng, branches, b, axes, distal)
    if rng.random() < 0.5:  # a second fork half-way down one child
        b = int(rng.choice(main_children))
        at = len(branches[b]["points"]) // 2
        r0 = round(branches[b]["radius"][at] * rng.uniform(0.65, 0.9), 3)
        angle = (1 if rng.random() < 0.5 else -1) * rng.uniform(20, 60)
        branches.append(child_branch(branches, b, at, angle, 5 * rng.integers(6, 10), rng.uniform(-0.01, 0.01),
                                     r0, distal(r0), axes, f"F{len(branches)}"))
    return branches


def too_close(branches):
    """True when two branches come closer than their radii + 0.6 mm away from the junctions between them."""
    dense = []
    for b in branches:
        pts, rad = np.array(b["points"]), np.array(b["radius"])
        t = np.linspace(0, len(pts) - 1, 4 * (len(pts) - 1) + 1)
        dense.append((np.array([np.interp(t, np.arange(len(pts)), pts[:, k]) for k in range(3)]).T,
                      np.interp(t, np.arange(len(pts)), rad)))
    for i in range(len(branches)):
        for j in range(i):
            (pi, ri), (pj, rj) = dense[i], dense[j]
            # a child's first 3 x (radius sum) + 2 mm is its junction: left out (the stem has none)
            skip = 3 * (ri.max() + rj.max()) + 2
            near_i = (np.arange(len(pi)) * STEP_MM / 4 < skip) & (branches[i]["parent"] is not None)
            near_j = (np.arange(len(pj)) * STEP_MM / 4 < skip) & (branches[j]["parent"] is not None)
            d = np.linalg.norm(pi[~near_i][:, None] - pj[~near_j][None], axis=2)
            if d.size and (d - ri[~near_i][:, None] - rj[~near_j][None]).min() < 0.6:
                return True
    return False


def sample_coronary(rng, name):
    """One coronary tree spec (retried until its branches keep clear of each other and it has 2-8 targets)."""
    for _ in range(100):
        a = rng.uniform(30, 40)
        axes = np.array([a, a * rng.uniform(0.9, 1.1), rng.uniform(45, 55)])
        branches = sample_coronary_branches(rng, axes)
        targets = len(branches) - 1  # every branch end but the stem's, which is the fork
        if not too_close(branches) and 2 <= targets <= MAX_TARGETS:
            break
    else:
        raise RuntimeError(f"{name}: no tree kept clear in 100 draws")
    spec = {"name": name, "description": "Drawn by gw-anatomy-pool (coronary tree on an ellipsoidal heart, "
                                         f"semi-axes {', '.join(f'{x:.1f}' for x in axes)} mm).",
            "units": "mm", "branches": [spec_branch(branches, b, axes) for b in branches]}
    if rng.random() < 0.3:
        spec["deformation"] = {"center": [0, 0, 0], "axis": [0, 0, -1],
                               "radial_contraction": round(rng.uniform(0.06, 0.14), 3),
                               "axial_shortening": round(rng.uniform(0.04, 0.12), 3),
                               "twist_deg_per_cm": round(rng.uniform(0.0, 4.0), 2),
                               "phase": round(rng.uniform(0.3, 1.0), 3)}
    return spec


def arch_module():
    path = REPO / "anatomies" / "segmentation" / "make_arch_specs.py"
    spec = importlib.util.spec_from_file_location("make_arch_specs", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def sample_arch(rng, name):
    """One aortic arch spec: make_arch_specs' construction, height 26-52 mm, great-vessel angles drawn apart."""
    m = arch_module()
    height = rng.uniform(26, 52)
    theta_bct = rng.uniform(112, 158)
    theta_lcca = theta_bct - rng.uniform(18, 40)
    theta_lsa = theta_lcca - rng.uniform(20, 40)
    description = (f"Drawn by gw-anatomy-pool: aortic arch {height:.0f} mm high, great vessels at "
                   f"{theta_bct:.0f}/{theta_lcca:.0f}/{theta_lsa:.0f} deg of the arc, drop {{drop_mm}} mm.")
    spec, _ = m.arch(name, height, theta_bct, theta_lcca, theta_lsa, description)
    return spec


def heart(seed, name):
    """--beating: the cardiac field (at phase 0: the mesh is its rest shape) and rate of coronary sample `name`,
    drawn apart from its spec: amplitudes as the deformed trees' (radial 6-14 %, axial 4-12 %, twist 0-4
    degrees/cm), rate 0-120 bpm."""
    rng = np.random.default_rng([seed, int(name.rsplit("_", 1)[1]), BEAT_STREAM, 0])
    field = {"center": [0, 0, 0], "axis": [0, 0, -1], "radial_contraction": round(rng.uniform(0.06, 0.14), 3),
             "axial_shortening": round(rng.uniform(0.04, 0.12), 3),
             "twist_deg_per_cm": round(rng.uniform(0.0, 4.0), 2), "phase": 0}
    return field, round(rng.uniform(0, MAX_HEART_RATE_BPM), 1)


def sample_spec(seed, index, kinds, redraw=0, beating=False):
    """Sample `index` of pool `seed`: its kind and spec. Redraw k > 0 (after the generator refused the spec) is
    drawn from (seed, index, k) instead, under the same name. `beating`: a coronary tree's deformation is replaced
    by its heart's field at phase 0 (heart())."""
    rng = np.random.default_rng([seed, index] if redraw == 0 else [seed, index, redraw])
    kind = kinds[int(rng.integers(len(kinds)))]
    name = f"{kind}_{seed}_{index:04d}"
    spec = (sample_arch if kind == "arch" else sample_coronary)(rng, name)
    if beating and kind == "coronary":
        spec["deformation"], rate = heart(seed, name)
        spec["description"] += f" Beats at {rate} bpm (gw-anatomy-pool --beating; the mesh is the rest shape)."
    if redraw:
        spec["description"] += f" Redraw {redraw}: anatomy-gen refused the earlier draws."
    return kind, spec


@functools.lru_cache(maxsize=None)
def base_wire_text(kind):
    """The shipped wire JSON of `kind` (BASE_WIRES), read once per run."""
    return (REPO / "engine" / "wire" / BASE_WIRES[kind]).read_text()


def drawn_wire(seed, name, kind):
    """--vary-wires: the kind's shipped wire with its tip length, tip bend and friction drawn for sample `name`."""
    wire = json.loads(base_wire_text(kind))
    rng = np.random.default_rng([seed, int(name.rsplit("_", 1)[1]), WIRE_STREAM, 0])
    r = WIRE_RANGES[kind]
    length = rng.uniform(*r["tip_length_mm"])
    bend = math.radians(rng.uniform(*r["tip_bend_deg"]))
    wire.update(tip_length_mm=round(length, 3), tip_curvature_per_mm=round(bend / length, 5),
                friction=round(rng.uniform(*r["friction"]), 4))
    wire["comment"] = (f"Drawn by gw-anatomy-pool --vary-wires for {name}: {BASE_WIRES[kind]} with the tip bent "
                       f"{math.degrees(bend):.0f} degrees over {length:.1f} mm and friction {wire['friction']}.")
    return wire


def write_index(out, entries, seed=0, vary_wires=False, beating=False):
    """OUT/index.json in anatomies/index.json's format, paths relative to OUT's parent. A kind with its own wire
    (KIND_WIRES: the aortic arches') gets that wire's JSON copied to OUT/wires/ and named by its entries, so that
    one server serves a pool of coronary trees and arches, each with its wire; with `vary_wires` every entry names
    its own drawn wire, OUT/wires/<name>.json; with `beating` a coronary entry names its heart rate."""
    rel = out.name
    rows = []
    for k, n in entries:
        row = {"name": n, "set": k, "mesh": f"{rel}/{k}/{n}/{n}.stl", "truth": f"{rel}/{k}/{n}/{n}.truth.json",
               "spec": f"{rel}/{k}/{n}/{n}.spec.json"}
        if vary_wires or k in KIND_WIRES:
            (out / "wires").mkdir(parents=True, exist_ok=True)
            file = f"{n}.json" if vary_wires else KIND_WIRES[k]
            if vary_wires:
                (out / "wires" / file).write_text(json.dumps(drawn_wire(seed, n, k), indent=1) + "\n")
            else:
                shutil.copyfile(REPO / "engine" / "wire" / file, out / "wires" / file)
            row["wire"] = f"{rel}/wires/{file}"
        if beating and k == "coronary":
            row["heart_rate_bpm"] = heart(seed, n)[1]
        rows.append(row)
    (out / "index.json").write_text(json.dumps({"anatomies": rows}, indent=1) + "\n")


def mesh_one(anatomy_gen, folder, name):
    """Runs anatomy-gen on one spec unless its mesh and truth are already there; returns its summary or error."""
    if (folder / f"{name}.stl").exists() and (folder / f"{name}.truth.json").exists():
        return {"name": name, "kept": True}
    r = subprocess.run([anatomy_gen, "--spec", str(folder / f"{name}.spec.json"), "--out", str(folder)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return {"name": name, "error": (r.stderr or r.stdout).strip().splitlines()[-1:]}
    return json.loads(r.stdout.strip().splitlines()[-1])


def parse_args(argv=None):
    p = argparse.ArgumentParser(prog="gw-anatomy-pool", description=__doc__.split("\n\n")[0])
    p.add_argument("--out", required=True, help="pool folder (created; meshes already there are kept)")
    p.add_argument("--count", type=int, required=True, help="number of anatomies")
    p.add_argument("--seed", type=int, required=True, help="pool seed: sample i is drawn from (seed, i)")
    p.add_argument("--kinds", default="coronary",
                   help="comma list of: coronary, arch (an arch's index entry names the aortic wire)")
    p.add_argument("--jobs", type=int, default=1, help="anatomy-gen processes at once")
    p.add_argument("--anatomy-gen", default=None, help="the anatomy-gen binary (default: $GW_BUILD_DIR/apps)")
    p.add_argument("--specs-only", action="store_true", help="write the specs and index, mesh nothing")
    p.add_argument("--beating", action="store_true",
                   help="every coronary tree beats: a cardiac field at phase 0 and a rate of 0-120 bpm, drawn")
    p.add_argument("--vary-wires", action="store_true",
                   help="each anatomy its own wire: its kind's with tip length, tip bend and friction drawn")
    args = p.parse_args(argv)
    kinds = [k.strip() for k in args.kinds.split(",") if k.strip()]
    if not kinds or any(k not in KINDS for k in kinds):
        p.error(f"--kinds: {args.kinds!r}: each kind must be one of {', '.join(KINDS)}")
    if args.count < 1 or args.jobs < 1:
        p.error("--count and --jobs must be at least 1")
    args.kinds = kinds
    return args


def write_spec(out, kind, spec):
    """OUT/<kind>/<name>/<name>.spec.json, unless that anatomy is already meshed (its spec may be a redraw). A meshed
    first draw whose spec is not this one was drawn with other options (--beating): refused, naming it."""
    folder = out / kind / spec["name"]
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{spec['name']}.spec.json"
    if not ((folder / f"{spec['name']}.stl").exists() and (folder / f"{spec['name']}.truth.json").exists()):
        path.write_text(json.dumps(spec, indent=1) + "\n")
    elif path.exists() and "Redraw" not in (kept := json.loads(path.read_text())).get("description", "") \
            and kept != spec:
        sys.exit(f"error: {path}: this pool was drawn with other options (--beating with or without?): its meshed "
                 "anatomy's spec is not this draw's; use another --out")
    return kind, spec["name"]


def mesh_or_redraw(gen, out, seed, index, kinds, entry, beating=False):
    """Meshes sample `index`; when anatomy-gen refuses its spec (e.g. two branches that intersect, which the
    sampler's own clearance test did not see), draws it again (up to MAX_REDRAWS times) and meshes that."""
    result = mesh_one(gen, out / entry[0] / entry[1], entry[1])
    for redraw in range(1, MAX_REDRAWS + 1):
        if "error" not in result:
            break
        kind, spec = sample_spec(seed, index, kinds, redraw, beating)
        entry = write_spec(out, kind, spec)
        result = mesh_one(gen, out / kind / spec["name"], spec["name"])
        result["redraw"] = redraw
    return result


def main(argv=None):
    args = parse_args(argv)
    out = Path(args.out)
    entries = [write_spec(out, *sample_spec(args.seed, i, args.kinds, beating=args.beating)) for i in range(args.count)]
    write_index(out, entries, args.seed, args.vary_wires, args.beating)
    if args.specs_only:
        print(json.dumps({"out": str(out), "specs": len(entries)}))
        return 0
    gen = args.anatomy_gen or str(app_path("anatomy-gen"))
    if not Path(gen).exists():
        sys.exit(f"error: --anatomy-gen: {gen}: not found (build the project first)")
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda i: mesh_or_redraw(gen, out, args.seed, i, args.kinds, entries[i], args.beating),
                                range(len(entries))))
    failed = [r for r in results if "error" in r]
    for r in results:
        print(json.dumps(r))
    if failed:  # a failed spec is dropped from the index, named here
        write_index(out, [e for e, r in zip(entries, results) if "error" not in r], args.seed, args.vary_wires,
                    args.beating)
        print(f"error: {len(failed)} of {len(entries)} specs failed to mesh: "
              + ", ".join(r["name"] for r in failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
