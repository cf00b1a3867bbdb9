"""Writes syn_validation.spec.json (run from this folder; then anatomy-gen --spec ... --out .).

A validation tree with the synthetic rows' bifurcation shapes but none of their geometries: constant
radius 1.75 mm like the training patterns, a trunk curving 35 deg in plane, a 45 deg exit on the
outer side of that bend (the kind of take-off of t2 and var1), an asymmetric fork whose plane is
turned out of the trunk's (var2, the unseen tree's fork), and a side branch leaving a straight vessel
mid-way at 55 deg (the unseen tree's side branches). Why: the coronary-like validation trees alone
did not see a regression on these shapes (a weight-averaged actor scored 8 more of 220 validation
episodes than the shipped one and lost 5 of 89 reachable training episodes, all t2 target 1;
policy/trained/README.md). Every take-off is on the outer side of a bend or on a straight vessel, so
the 6 mm, 0.2/mm tip can reach every target (checked with the scripted controller).
"""

import json
import math

import numpy as np

STEP_MM = 5.0
RADIUS = 1.75


def rotate(d, axis, angle):
    axis = axis / np.linalg.norm(axis)
    return d * math.cos(angle) + np.cross(axis, d) * math.sin(angle) + axis * axis.dot(d) * (1 - math.cos(angle))


def walk(p, d, segments):
    """Points and unit directions along `segments`: (length mm, turn in deg, turn axis), in 5 mm steps,
    each step turning by its share of the segment's angle."""
    points, directions = [np.asarray(p, float)], [np.asarray(d, float)]
    for length, turn_deg, axis in segments:
        steps = int(round(length / STEP_MM))
        for _ in range(steps):
            d = rotate(directions[-1], np.asarray(axis, float), math.radians(turn_deg) / steps)
            points.append(points[-1] + STEP_MM * d)
            directions.append(d / np.linalg.norm(d))
    return points, directions


def off(d, normal, angle_deg):
    """Direction leaving `d` at `angle_deg`, turned towards `normal` (made perpendicular to d)."""
    n = np.asarray(normal, float) - d * d.dot(normal)
    return rotate(d, np.cross(d, n), math.radians(angle_deg))


z, y = np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
# Trunk: 15 mm straight, then 35 deg towards +x over 45 mm (centre of curvature on +x: the outer wall is -x).
trunk, trunk_d = walk([0, 0, 0], z, [(15, 0, y), (45, 35, y)])
b1 = len(trunk) - 1
# Exit 1: 45 deg off the trunk's end on the outer (-x) side, tilted 20 deg out of plane, bending on by 15 deg.
d1 = rotate(off(trunk_d[b1], [-1, 0, 0], 45), trunk_d[b1], math.radians(20))
exit1, _ = walk(trunk[b1], d1, [(50, 15, np.cross(d1, [-1, 0, 0]))])
# Continuation: straight on for 40 mm with a gentle 10 deg out-of-plane drift, then 20 mm straight.
cont, cont_d = walk(trunk[b1], trunk_d[b1], [(40, 10, [1, 0, 0]), (20, 0, y)])
b3 = 5  # side branch 25 mm along the continuation (straight part of the drift), 55 deg towards -y
side, _ = walk(cont[b3], off(cont_d[b3], [0, -1, 0], 55), [(45, -10, [1, 0, 0])])
# Fork at the continuation's end, its plane turned 60 deg about the vessel: +35 and -30 deg.
e = cont_d[-1]
fork_normal = rotate(np.cross(e, y), e, math.radians(60))
fork_a, _ = walk(cont[-1], off(e, fork_normal, 35), [(50, 10, np.cross(e, fork_normal))])
fork_b, _ = walk(cont[-1], off(e, -fork_normal, 30), [(50, -10, np.cross(e, fork_normal))])


def pts(points):
    return [[round(float(x), 3) for x in p] for p in points]


spec = {
    "name": "syn_validation",
    "description": "Validation (checkpoint choice only, in no row of the table): constant radius 1.75 mm; a trunk curving "
                   "35 deg in plane, a 45 deg exit on the outer side of the bend, a 55 deg side branch mid-way along the "
                   "continuation and an asymmetric +35/-30 deg fork turned out of the trunk's plane. Written by make_spec.py.",
    "units": "mm",
    "branches": [
        {"name": "trunk", "points": pts(trunk), "radius": RADIUS},
        {"name": "exit1", "parent": 0, "points": pts(exit1), "radius": RADIUS},
        {"name": "continuation", "parent": 0, "points": pts(cont), "radius": RADIUS},
        {"name": "side", "parent": 2, "points": pts(side), "radius": RADIUS},
        {"name": "fork_a", "parent": 2, "points": pts(fork_a), "radius": RADIUS},
        {"name": "fork_b", "parent": 2, "points": pts(fork_b), "radius": RADIUS},
    ],
}
# One branch per line, as the hand-written specs.
lines = ",\n".join("    " + json.dumps(b) for b in spec["branches"])
header = json.dumps({k: v for k, v in spec.items() if k != "branches"}, indent=2)[:-2]
with open("syn_validation.spec.json", "w") as f:
    f.write(header + ',\n  "branches": [\n' + lines + "\n  ]\n}\n")
