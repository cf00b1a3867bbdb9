"""Writes the junction test trees' specs (run from this folder with the project's .venv/bin/python; then anatomy-gen --spec NAME/NAME.spec.json --out NAME).

Two coronary-sized, tapering trees on the coronary's ellipsoidal heart (semi-axes 35, 35, 50 mm), with
junctions the training set never had (issue 41), designed before any run on them:
- coronary_trifurcation: the left main trifurcates (LAD, ramus intermedius, LCx at +35 / 0 / -40 deg),
  the LAD trifurcates again 35 mm on (two diagonals at +-30 deg), the LCx has one two-way fork.
- close_forks: forks one to two vessel diameters apart: D1 leaves the LAD 5 mm past the left main
  fork (1.4 LAD diameters), OM1 leaves the LCx 5 mm past it (1.6 diameters), and two LAD side branches
  leave 5 mm apart on opposite sides further down (1.8 diameters).
Take-offs are 25-40 deg and the parents nearly straight (0.004-0.006 /mm), so no branch leaves on the inner
side of a sharp bend (unreachable for this wire, anatomies/README.md "Reachable by design").
Each branch is a walk on the ellipsoid in 5 mm steps at constant geodesic curvature; centrelines sit
radius + 0.3 mm off the surface, as in the coronary (the same construction as pl_validation/make_spec.py).
"""

import json
import math
import os

import numpy as np

from guidewire_nav.heart_walk import on_surface, rotate, spec_branch, surface_normal, taper, walk


def left_main(length_mm):
    """The coronary's left main: from its ostium high on the anterior wall, heading down."""
    start = on_surface(np.array([-13.917, 19.876, 45.776]))
    n0 = surface_normal(start)
    d = np.array([0.241, 4.467, -8.179])
    d = d - n0 * n0.dot(d)
    points, directions = walk(start, d / np.linalg.norm(d), length_mm, 0.0)
    return dict(name="left_main", parent=None, at=None, points=points, directions=directions,
                radius=[2.0] * len(points))


def build(children):
    """children: (name, parent index, parent point index (x 5 mm), take-off deg, length mm, curvature, r0)."""
    branches = [left_main(15)]
    for name, parent, at, angle_deg, length, curvature, r0 in children:
        p = branches[parent]["points"][at]
        d = rotate(branches[parent]["directions"][at], surface_normal(p), math.radians(angle_deg))
        points, directions = walk(p, d, length, curvature)
        branches.append(dict(name=name, parent=parent, at=at, points=points, directions=directions,
                             radius=taper(len(points), r0, 0.8)))
    return branches


TREES = {
    "coronary_trifurcation": (
        "Junction test: left-coronary-like tree on the coronary's ellipsoidal heart whose left main (r 2.0) "
        "trifurcates into LAD (+35 deg), ramus intermedius (straight on) and LCx (-40 deg); the LAD "
        "trifurcates again 35 mm on (diagonals D1 +30 deg, D1b -30 deg); one two-way fork (OM1, -35 deg) "
        "on the LCx. Tapering to 0.8 mm. Written by make_specs.py (issue 41).",
        [("LAD", 0, 3, 35, 90, 0.004, 1.8),
         ("ramus", 0, 3, 0, 55, 0.0, 1.4),
         ("LCx", 0, 3, -40, 80, -0.006, 1.6),
         ("D1", 1, 7, 30, 40, 0.0, 1.1),
         ("D1b", 1, 7, -30, 35, 0.0, 1.0),
         ("OM1", 3, 7, -35, 40, 0.0, 1.1)]),
    "close_forks": (
        "Junction test: left-coronary-like tree on the coronary's ellipsoidal heart with forks one to two "
        "vessel diameters apart: left main (r 2.0) forks into LAD (+30 deg) and LCx (-40 deg); D1 (+35 deg) "
        "leaves the LAD 5 mm past that fork and OM1 (-35 deg) the LCx 5 mm past it; D2 (+30 deg) and S1 "
        "(-30 deg) leave the LAD 5 mm apart 40 mm on. Tapering to 0.8 mm. Written by make_specs.py (issue 41).",
        [("LAD", 0, 3, 30, 90, 0.004, 1.8),
         ("LCx", 0, 3, -40, 80, -0.006, 1.6),
         ("D1", 1, 1, 35, 45, 0.0, 1.2),
         ("OM1", 2, 1, -35, 45, 0.0, 1.2),
         ("D2", 1, 8, 30, 35, 0.0, 1.0),
         ("S1", 1, 9, -30, 35, 0.0, 1.0)]),
    # Corrected pair (2026-12-02), beside the frozen trees above: the rows of those two showed side branches
    # leaving on the inner side of a turn, which no controller or rotation schedule reached (results/junctions).
    # The same correction as anatomies/README.md "Reachable by design": each such branch turned 180 degrees
    # about its parent's direction at the take-off (angle and shape unchanged); where a k-way junction has
    # exits on both sides, the parent is made straight before it so neither side is the inner one.
    "coronary_trifurcation_outer": (
        "Junction test, corrected: coronary_trifurcation with the LAD straight before its trifurcation (the frozen "
        "tree's LAD bends +0.004/mm towards D1, putting D1 on the inner side) and OM1 turned to the outer side of "
        "the LCx's turn (+35 deg). Written by make_specs.py (issue 41).",
        [("LAD", 0, 3, 35, 90, 0.0, 1.8),
         ("ramus", 0, 3, 0, 55, 0.0, 1.4),
         ("LCx", 0, 3, -40, 80, -0.006, 1.6),
         ("D1", 1, 7, 30, 40, 0.0, 1.1),
         ("D1b", 1, 7, -30, 35, 0.0, 1.0),
         ("OM1", 3, 7, 35, 40, 0.0, 1.1)]),
    "close_forks_outer": (
        "Junction test, corrected: close_forks with D1 (-35 deg) and OM1 (+35 deg) turned to the outer side of the "
        "left main fork's turn into their parents (the frozen tree's D1 and OM1 leave on its inner side). "
        "Written by make_specs.py (issue 41).",
        [("LAD", 0, 3, 30, 90, 0.004, 1.8),
         ("LCx", 0, 3, -40, 80, -0.006, 1.6),
         ("D1", 1, 1, -35, 45, 0.0, 1.2),
         ("OM1", 2, 1, 35, 45, 0.0, 1.2),
         ("D2", 1, 8, 30, 35, 0.0, 1.0),
         ("S1", 1, 9, -30, 35, 0.0, 1.0)]),
}

for name, (description, children) in TREES.items():
    branches = build(children)
    spec = {"name": name, "description": description, "units": "mm",
            "branches": [spec_branch(branches, b) for b in branches]}
    os.makedirs(name, exist_ok=True)
    with open(os.path.join(name, name + ".spec.json"), "w") as f:
        json.dump(spec, f, indent=1)
