"""Writes the k-way junction training patterns' specs (run from this folder; then
anatomy-gen --spec NAME/NAME.spec.json --out NAME, or anatomy-gen --regenerate anatomies).

Issue 41, item 4: every junction of the paper's four training patterns (anatomies/train) is a two-way fork,
so an actor trained there has never aimed away from two wrong exits at once. These two patterns add the
three-way junction, in the training patterns' style (constant radius, exits 60-70 mm long, a straight or
gently curved access), and nothing of any test tree (written from the issue's description of a trifurcation,
not from the test trees' specs):
- t5_trifurcation_planar: straight access into three exits in one plane, -35 / 0 / +35 deg, the side exits
  bending gently away (as t1's).
- t6_trifurcation_spread: access curved 30 deg out of the exits' symmetry, three exits 35 deg off the axis and
  120 deg apart around it, so no exit is straight on and each one's two wrong exits lie on either side.
They form the set "train_junctions" (anatomies/index.json); the paper's recipe keeps "train" (4 patterns).
"""

import json
import math

import numpy as np

STEP_MM = 5.0
TRUNK_R = 1.75
EXIT_R = 1.5


def rotate(d, axis, angle):
    axis = axis / np.linalg.norm(axis)
    return d * math.cos(angle) + np.cross(axis, d) * math.sin(angle) + axis * axis.dot(d) * (1 - math.cos(angle))


def arc(p, d, bend_axis, length_mm, curvature_per_mm):
    """Points of a walk from p along unit d, turning about bend_axis at a constant curvature."""
    points = [p]
    for _ in range(int(round(length_mm / STEP_MM))):
        p = p + STEP_MM * d
        d = rotate(d, bend_axis, curvature_per_mm * STEP_MM)
        points.append(p)
    return points, d


def rounded(points):
    return [[round(float(x), 3) for x in p] for p in points]


def exits(junction, axis, side_axes, angle_deg, length_mm, curvature):
    """One exit per (direction of tilt) in side_axes: leaves `angle_deg` off `axis` towards it and bends away."""
    out = []
    for name, towards in side_axes:
        if towards is None:
            d, bend = axis, np.array([0.0, 1.0, 0.0])
            pts, _ = arc(junction, d, bend, length_mm, 0.0)
        else:
            towards = towards - axis * axis.dot(towards)
            towards /= np.linalg.norm(towards)
            bend = np.cross(axis, towards)
            d = rotate(axis, bend, math.radians(angle_deg))
            pts, _ = arc(junction, d, bend, length_mm, curvature)
        out.append({"name": name, "parent": 0, "points": rounded(pts), "radius": EXIT_R})
    return out


def t5():
    access, _ = arc(np.zeros(3), np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0]), 60, 0.0)
    j, axis = access[-1], np.array([0.0, 0.0, 1.0])
    x = np.array([1.0, 0.0, 0.0])
    return {
        "name": "t5_trifurcation_planar",
        "description": "Training 5 (k-way junctions): straight access into a planar trifurcation, exits at -35, 0 and "
                       "+35 degrees, the side exits bending gently away. Written by make_specs.py (issue 41).",
        "units": "mm",
        "branches": [{"name": "access", "points": rounded(access), "radius": TRUNK_R}] +
                    exits(j, axis, [("left", -x), ("straight", None), ("right", x)], 35, 65, 0.004),
    }


def t6():
    # Access: 20 mm straight, then 30 deg of bend (curvature 0.015 /mm) in the y-z plane, then 10 mm straight.
    start, d = np.zeros(3), np.array([0.0, 0.0, 1.0])
    a, _ = arc(start, d, np.array([1.0, 0.0, 0.0]), 20, 0.0)
    b, d = arc(a[-1], d, np.array([1.0, 0.0, 0.0]), 35, math.radians(30) / 35)
    c, _ = arc(b[-1], d, np.array([1.0, 0.0, 0.0]), 10, 0.0)
    access = a + b[1:] + c[1:]
    j, axis = access[-1], d / np.linalg.norm(d)
    u = np.cross(axis, np.array([1.0, 0.0, 0.0]))
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    # Exits 120 deg apart, the first at 90 deg from the access's bend plane (so none is on its inner side).
    towards = [rotate(v, axis, math.radians(a_)) for a_ in (0.0, 120.0, 240.0)]
    return {
        "name": "t6_trifurcation_spread",
        "description": "Training 6 (k-way junctions): access curved 30 degrees, then a trifurcation whose three exits "
                       "leave 35 degrees off the axis, 120 degrees apart around it, bending gently away. "
                       "Written by make_specs.py (issue 41).",
        "units": "mm",
        "branches": [{"name": "access", "points": rounded(access), "radius": TRUNK_R}] +
                    exits(j, axis, [("a", towards[0]), ("b", towards[1]), ("c", towards[2])], 35, 60, 0.004),
    }


if __name__ == "__main__":
    import os
    for spec in (t5(), t6()):
        os.makedirs(spec["name"], exist_ok=True)
        with open(os.path.join(spec["name"], spec["name"] + ".spec.json"), "w") as f:
            json.dump(spec, f, indent=1)
            f.write("\n")
