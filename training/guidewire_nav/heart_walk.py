"""Coronary-like vessels walked over an ellipsoidal heart: the one construction of the generated coronary trees.

Inputs: a start point, a direction, a length and a geodesic curvature; the heart's semi-axes (default 35, 35,
50 mm, the committed coronary's). Outputs: centreline points every 5 mm on the surface, their directions, and the
points lifted off the surface by radius + 0.3 mm, as the committed coronary trees are built
(anatomies/junctions/make_specs.py, anatomies/validation/pl_validation/make_spec.py, the anatomy pool).
"""

import math

import numpy as np

AXES = np.array([35.0, 35.0, 50.0])
STEP_MM = 5.0


def on_surface(p, axes=AXES):
    return p / math.sqrt(((p / axes) ** 2).sum())


def surface_normal(p, axes=AXES):
    n = p / axes ** 2
    return n / np.linalg.norm(n)


def rotate(d, axis, angle):
    return d * math.cos(angle) + np.cross(axis, d) * math.sin(angle) + axis * axis.dot(d) * (1 - math.cos(angle))


def walk(p, d, length_mm, curvature_per_mm, axes=AXES):
    """Points and unit directions of a walk on the surface starting at p along d."""
    points, directions = [p], [d]
    for _ in range(int(round(length_mm / STEP_MM))):
        n = surface_normal(p, axes)
        d = rotate(d - n * n.dot(d), n, curvature_per_mm * STEP_MM)
        d /= np.linalg.norm(d)
        p = on_surface(p + STEP_MM * d, axes)
        points.append(p)
        directions.append(d)
    return points, directions


def taper(n, r0, r1):
    return [round(r0 + (r1 - r0) * i / max(n - 1, 1), 3) for i in range(n)]


def lifted(points, radii, axes=AXES):
    return [[round(float(x), 3) for x in p + surface_normal(p, axes) * (r + 0.3)] for p, r in zip(points, radii)]


def spec_branch(branches, b, axes=AXES):
    """One branch of a tree spec; a child starts exactly on its parent's centreline (lifted by the parent's
    radius there). b: {name, parent (index or None), at (parent point index), points, radius}."""
    out = {"name": b["name"], "points": lifted(b["points"], b["radius"], axes), "radius": b["radius"]}
    if b["parent"] is not None:
        parent = branches[b["parent"]]
        out["points"][0] = lifted([parent["points"][b["at"]]], [parent["radius"][b["at"]]], axes)[0]
        out["parent"] = b["parent"]
    return out
