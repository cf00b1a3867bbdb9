"""Writes pl_validation.spec.json (run from this folder; then anatomy-gen --spec ... --out .).

A validation tree with the coronary's difficulty but not its shape: a posterolateral vessel walked
over the same ellipsoidal heart (semi-axes 35, 35, 50 mm), with four side branches leaving at
25-30 deg, the shallow take-offs that decide the coronary rows. Each branch is a walk on the
ellipsoid in 5 mm steps at constant geodesic curvature; centrelines sit radius + 0.3 mm off the
surface, as in the coronary.
"""

import json
import math

import numpy as np

AXES = np.array([35.0, 35.0, 50.0])
STEP_MM = 5.0


def on_surface(p):
    return p / math.sqrt(((p / AXES) ** 2).sum())


def surface_normal(p):
    n = p / AXES ** 2
    return n / np.linalg.norm(n)


def rotate(d, axis, angle):
    return d * math.cos(angle) + np.cross(axis, d) * math.sin(angle) + axis * axis.dot(d) * (1 - math.cos(angle))


def walk(p, d, length_mm, curvature_per_mm):
    """Points and unit directions of a walk on the surface starting at p along d."""
    points, directions = [p], [d]
    for _ in range(int(round(length_mm / STEP_MM))):
        n = surface_normal(p)
        d = rotate(d - n * n.dot(d), n, curvature_per_mm * STEP_MM)
        d /= np.linalg.norm(d)
        p = on_surface(p + STEP_MM * d)
        points.append(p)
        directions.append(d)
    return points, directions


def taper(n, r0, r1):
    return [round(r0 + (r1 - r0) * i / (n - 1), 3) for i in range(n)]


def lifted(points, radii):
    return [[round(float(x), 3) for x in p + surface_normal(p) * (r + 0.3)] for p, r in zip(points, radii)]


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


def spec_branch(b):
    out = {"name": b["name"], "points": lifted(b["points"], b["radius"]), "radius": b["radius"]}
    if b["parent"] is not None:
        # A child starts exactly on its parent's centreline (lifted by the parent's radius there).
        parent = branches[b["parent"]]
        out["points"][0] = lifted([parent["points"][b["at"]]], [parent["radius"][b["at"]]])[0]
        out["parent"] = b["parent"]
    return out


spec = {
    "name": "pl_validation",
    "description": "Validation (not in the results table): posterolateral-like tree on the coronary's "
                   "ellipsoidal heart, four side branches leaving at 25-30 deg (shallow, as in the coronary), "
                   "r 1.9 -> 0.8 mm. Used with rca_validation to choose between training checkpoints.",
    "units": "mm",
    "branches": [spec_branch(b) for b in branches],
}
with open("pl_validation.spec.json", "w") as f:
    json.dump(spec, f, indent=1)
