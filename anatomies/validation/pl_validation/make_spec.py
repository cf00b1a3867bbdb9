"""Writes pl_validation.spec.json (run from this folder with the project's .venv/bin/python; then anatomy-gen --spec ... --out .).

A validation tree with the coronary's difficulty but not its shape: a posterolateral vessel walked
over the same ellipsoidal heart (semi-axes 35, 35, 50 mm), with four side branches leaving at
25-30 deg, the shallow take-offs that decide the coronary rows. Each branch is a walk on the
ellipsoid in 5 mm steps at constant geodesic curvature; centrelines sit radius + 0.3 mm off the
surface, as in the coronary.
"""

import json
import math

import numpy as np

from guidewire_nav.heart_walk import on_surface, rotate, spec_branch, surface_normal, taper, walk

# Main vessel: from high on the posterior wall, heading down and 35 deg to the side.
u, v = math.radians(215), math.radians(40)
start = on_surface(np.array([35 * math.cos(v) * math.cos(u), 35 * math.cos(v) * math.sin(u), 50 * math.sin(v)]))
n0 = surface_normal(start)
down = np.array([0.0, 0.0, -1.0])
heading = rotate((down - n0 * n0.dot(down)) / np.linalg.norm(down - n0 * n0.dot(down)), n0, math.radians(-35))
points, directions = walk(start, heading, 120, 0.006)
branches = [dict(name="PL", parent=None, at=None, points=points, directions=directions, radius=taper(len(points), 1.9, 1.0))]

# Side branches: (name, parent index, parent point index (x 5 mm), take-off angle, length, curvature, radius).
for name, parent, at, angle_deg, length, curvature, r0 in [
    ("PL1", 0, 8, 30, 50, -0.004, 1.3),
    ("PL2", 0, 12, -25, 55, 0.004, 1.3),
    ("PL3", 0, 17, 30, 40, 0.0, 1.1),
    ("PL2a", 2, 4, 30, 35, 0.0, 1.0),
]:
    p = branches[parent]["points"][at]
    d = rotate(branches[parent]["directions"][at], surface_normal(p), math.radians(angle_deg))
    points, directions = walk(p, d, length, curvature)
    branches.append(dict(name=name, parent=parent, at=at, points=points, directions=directions,
                         radius=taper(len(points), r0, 0.8)))


spec = {
    "name": "pl_validation",
    "description": "Validation (not in the results table): posterolateral-like tree on the coronary's "
                   "ellipsoidal heart, four side branches leaving at 25-30 deg (shallow, as in the coronary), "
                   "r 1.9 -> 0.8 mm. Used with rca_validation to choose between training checkpoints.",
    "units": "mm",
    "branches": [spec_branch(branches, b) for b in branches],
}
with open("pl_validation.spec.json", "w") as f:
    json.dump(spec, f, indent=1)
