"""Writes the three aortic-arch specs of the segmentation set (Type I, II, III) beside this file.

    python anatomies/segmentation/make_arch_specs.py               # numpy only; prints each arch's measurements
    python anatomies/segmentation/make_arch_specs.py --validation  # three held-apart arches for choices
                                                                   # (anatomies/validation/arches/)
    python anatomies/segmentation/make_arch_specs.py --stubs       # those three with the great vessels cut to
                                                                   # stubs 1, 2 and 3 own radii long (9 arches)

Frame (mm): x to the patient's left, y posterior, z superior. The arch lies near the vertical plane
through the ascending and descending aorta, whose horizontal direction u runs from the ascending
(right, anterior) to the descending aorta (left, posterior); in-plane coordinates are (s along u, z).

Branch 0 (the root, whose first point is the inlet) runs up the descending aorta, over the arch and
down the ascending aorta to the sinotubular junction: the wire enters from the descending aorta as
in femoral access. The targets are the aortic root end and the three supra-aortic branches, which
leave the root branch as side branches (3 bifurcations, 4 targets).

Arch type (the clinical classification of arch elongation, Type I/II/III): the vertical distance from the top of the arch's outer curvature to the origin of the brachiocephalic
trunk, in left-common-carotid diameters: Type I < 1, Type II 1-2, Type III > 2. Measured here on the
splines: apex = max(z + r) over the root centreline; origin = the first point of the brachiocephalic
centreline outside the root's lumen (distance to the root centreline >= the root radius there).
"""
import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
U = np.array([0.6, 0.8, 0.0])             # horizontal, ascending -> descending
N = np.cross([0.0, 0.0, 1.0], U)          # horizontal normal of the arch plane (-0.8, 0.6, 0): right-ish
Z = np.array([0.0, 0.0, 1.0])
X = np.array([1.0, 0.0, 0.0])             # patient's left
Y = np.array([0.0, 1.0, 0.0])             # posterior
WIDTH = 58.0                              # ascending to descending centreline, mm
LCCA_R = 4.0


def plane(s, z, n=0.0):
    return s * U + z * Z + n * N


def catmull_rom_point(c, u):
    """The generator's centripetal Catmull-Rom (anatomy_gen/catmull_rom.cpp) at parameter u."""
    n = len(c)
    i = min(max(int(np.floor(u)), 0), n - 2)
    t = min(max(u - i, 0.0), 1.0)
    p1, p2 = c[i], c[i + 1]
    p0 = c[i - 1] if i > 0 else 2 * p1 - p2
    p3 = c[i + 2] if i + 2 < n else 2 * p2 - p1
    k = lambda a, b: max(np.sqrt(np.linalg.norm(b - a)), 1e-9)
    t0, t1 = 0.0, k(p0, p1)
    t2 = t1 + k(p1, p2)
    t3 = t2 + k(p2, p3)
    s = t1 + t * (t2 - t1)
    a1 = (t1 - s) / (t1 - t0) * p0 + (s - t0) / (t1 - t0) * p1
    a2 = (t2 - s) / (t2 - t1) * p1 + (s - t1) / (t2 - t1) * p2
    a3 = (t3 - s) / (t3 - t2) * p2 + (s - t2) / (t3 - t2) * p3
    b1 = (t2 - s) / (t2 - t0) * a1 + (s - t0) / (t2 - t0) * a2
    b2 = (t3 - s) / (t3 - t1) * a2 + (s - t1) / (t3 - t1) * a3
    return (t2 - s) / (t2 - t1) * b1 + (s - t1) / (t2 - t1) * b2


def catmull_rom(c, spacing=0.25):
    """Dense samples of the spline through control points c, and the parameter u of each."""
    c = np.asarray(c, float)
    us = [0.0]
    for i in range(len(c) - 1):
        steps = max(1, int(np.ceil(np.linalg.norm(c[i + 1] - c[i]) * 1.3 / spacing)))
        us += [i + j / steps for j in range(1, steps + 1)]
    return np.array([catmull_rom_point(c, u) for u in us]), np.array(us)


def radius_at(radius, us):
    return np.interp(us, np.arange(len(radius)), radius)


def arch(name, height, theta_bct, theta_lcca, theta_lsa, description):
    """Root branch points and radii, then the three branches leaving at arc angles theta (degrees;
    0 = top of the descending limb, 90 = apex, 180 = top of the ascending limb)."""
    pts, rad = [], []
    # Descending aorta from the inlet (about the level of T8) up to the arch, leaning slightly medially.
    for z, n, r in [(-95, -6, 10.0), (-70, -4, 10.3), (-45, -2, 10.6), (-20, -0.5, 10.9)]:
        pts.append(plane(WIDTH, z, n)); rad.append(r)
    # Arch: half an ellipse, semi-axes WIDTH/2 (horizontal) and `height` (vertical), a control point
    # every 15 degrees; radius 11 -> 13 mm from the descending to the ascending limb.
    first = len(pts)
    for t in range(0, 181, 15):
        a = np.radians(t)
        pts.append(plane(WIDTH / 2 + WIDTH / 2 * np.cos(a), height * np.sin(a)))
        rad.append(11.0 + 2.0 * t / 180.0)
    # Ascending aorta down to the sinotubular junction, bulging to the right and forwards.
    for z, s, r in [(-20, -2.5, 13.6), (-40, -3.0, 14.0), (-58, 0.0, 14.4)]:
        pts.append(plane(s, z)); rad.append(r)

    # Branch origins: the spline's point at arc angle theta (the parameter runs 1 per 15 degrees there),
    # so that they lie on the root centreline without a control point of their own (uneven control
    # points would kink the centripetal spline).
    origin = {key: catmull_rom_point(np.array(pts), first + theta / 15.0)
              for key, theta in (("bct", theta_bct), ("lcca", theta_lcca), ("lsa", theta_lsa))}

    def branch(key, dirs, lengths, radii):
        o = origin[key]
        p, out = o.copy(), [o]
        for d, l in zip(dirs, lengths):
            d = np.asarray(d, float) / np.linalg.norm(d)
            p = p + l * d
            out.append(p)
        return out, radii

    bct = branch("bct", [Z + 0.35 * -X - 0.15 * Y, Z + 0.55 * -X - 0.1 * Y, Z + 0.5 * -X], [22, 18, 18], [6.3, 6.1, 5.9, 5.7])
    lcca = branch("lcca", [Z + 0.05 * X, Z + 0.12 * X, Z + 0.08 * X], [25, 30, 30], [4.0, 3.9, 3.7, 3.5])
    lsa = branch("lsa", [Z + 0.35 * X + 0.1 * Y, Z + 0.6 * X + 0.1 * Y, 0.3 * Z + X], [22, 20, 22], [5.0, 4.8, 4.5, 4.2])
    branches = [{"name": "aorta_descending_arch_ascending", "points": pts, "radius": rad},
                {"name": "brachiocephalic", "parent": 0, "points": bct[0], "radius": bct[1]},
                {"name": "left_common_carotid", "parent": 0, "points": lcca[0], "radius": lcca[1]},
                {"name": "left_subclavian", "parent": 0, "points": lsa[0], "radius": lsa[1]}]
    return measure(name, branches, description)


def measure(name, branches, description):
    dense = [catmull_rom(b["points"]) for b in branches]
    radii = [radius_at(b["radius"], us) for b, (_, us) in zip(branches, dense)]
    root, rr = dense[0][0], radii[0]
    apex = float(np.max(root[:, 2] + rr))
    bct = dense[1][0]
    dist = np.linalg.norm(bct[:, None, :] - root[None, :, :], axis=2)
    outside = np.min(dist - rr[None, :], axis=1) >= 0
    origin_z = float(bct[np.argmax(outside), 2])
    drop = (apex - origin_z) / (2 * LCCA_R)
    # Clearance between branches and between each branch and the root, away from their junctions.
    gaps = {}
    for i in range(1, 4):
        far = np.min(np.linalg.norm(dense[i][0][:, None] - root[None], axis=2) - rr[None], axis=1) > 3.0
        for j in range(0, 4):
            if j == i:
                continue
            d = np.linalg.norm(dense[i][0][far][:, None] - dense[j][0][None], axis=2)
            g = d - radii[i][far][:, None] - radii[j][None]
            if j == 0:
                gaps[f"{branches[i]['name']}-root"] = round(float(g.min()), 1) if g.size else None
            elif j > i:
                gaps[f"{branches[i]['name']}-{branches[j]['name']}"] = round(float(g.min()), 1) if g.size else None
    bend = []
    for (p, _), r in zip(dense, radii):
        a, b, c = p[:-2], p[1:-1], p[2:]
        ab, bc, ca = (np.linalg.norm(b - a, axis=1), np.linalg.norm(c - b, axis=1), np.linalg.norm(a - c, axis=1))
        area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
        R = np.where(area2 > 1e-12, ab * bc * ca / np.maximum(area2, 1e-12), np.inf)
        bend.append(float(np.min(R / r[1:-1])))
    info = {"apex_z": round(apex, 1), "bct_origin_z": round(origin_z, 1), "drop_mm": round(apex - origin_z, 1),
            "drop_in_cca_diameters": round(drop, 2), "min_bend_radius_over_r": round(min(bend), 2), "gaps_mm": gaps}
    spec = {"name": name, "description": description.format(**info), "units": "mm", "branches": [
        {**b, "points": [[round(float(v), 3) for v in q] for q in b["points"]],
         "radius": [round(float(v), 3) for v in b["radius"]]} for b in branches]}
    return spec, info


COMMON = ("Aortic arch {type} for the segmentation-like set (issue 35), mm; frame x = patient's left, y = posterior, "
          "z = superior. Branch 0 starts at the INLET in the distal descending aorta (femoral access: the wire comes up "
          "the descending aorta), r 10 mm, rising to 11 mm at the arch, over the arch (r 11 -> 13 mm; ascending and "
          "descending centrelines {width:.0f} mm apart, arch {height:.0f} mm high above their tops) and down the ascending "
          "aorta (r 13.6 -> 14.4 mm) to the sinotubular junction, a target (the widest end, so `centerline` without "
          "--inlet would take it as the inlet: pass --inlet at the descending end). Side branches, 58-85 mm long from "
          "the aortic centreline: brachiocephalic trunk r 6.3 -> 5.7 mm (up and to the right), left common carotid "
          "r 4.0 -> 3.5 mm (up), left subclavian r 5.0 -> 4.2 mm (up and left, turning lateral). 4 targets, "
          "3 bifurcations. Arch type by the "
          "drop from the top of the outer curvature (z {{apex_z}}) to the brachiocephalic origin (where its centreline "
          "leaves the aortic lumen, z {{bct_origin_z}}): {{drop_mm}} mm = {{drop_in_cca_diameters}} left-common-carotid "
          "diameters (8 mm); {rule}. Written by make_arch_specs.py.")

ARCHES = [
    ("arch_type1", 28.0, 120, 95, 65, "Type I", "Type I is < 1"),
    ("arch_type2", 34.0, 140, 105, 70, "Type II", "Type II is 1-2"),
    ("arch_type3", 46.0, 155, 115, 75, "Type III", "Type III is > 2"),
]

# Validation arches: other heights and branch angles within the same types, for choices (planner settings, a
# controller's recipe) that must not be made on the measured arches above.
VALIDATION_ARCHES = [
    ("arch_val_type1", 30.0, 115, 90, 62, "Type I", "Type I is < 1"),
    ("arch_val_type2", 38.0, 135, 102, 68, "Type II", "Type II is 1-2"),
    ("arch_val_type3", 50.0, 150, 112, 72, "Type III", "Type III is > 2"),
]

def stub_arch(name, height, theta_bct, theta_lcca, theta_lsa, radii_out, description):
    """The arch with each great vessel cut short: a straight stub along its first direction, of its first radius,
    ending `radii_out` of its own radii outside the aortic lumen (as a phantom or a cropped scan shows them, the
    great vessels protruding 1-3 radii from the arch's roof). Returns the spec and, per stub, how far its end lies
    outside the aortic lumen (mm)."""
    spec, _ = arch(name, height, theta_bct, theta_lcca, theta_lsa, description)
    root, us = catmull_rom(spec["branches"][0]["points"])
    root_r = radius_at(spec["branches"][0]["radius"], us)
    out = {}
    for b in spec["branches"][1:]:
        p = np.asarray(b["points"], float)
        r = b["radius"][0]
        d = (p[1] - p[0]) / np.linalg.norm(p[1] - p[0])
        for t in np.arange(0.0, 100.0, 0.25):  # walk out of the aorta until the end is radii_out radii outside it
            end = p[0] + t * d
            outside = float(np.min(np.linalg.norm(root - end, axis=1) - root_r))
            if outside >= radii_out * r:
                break
        b["points"] = [[round(float(v), 3) for v in q] for q in (p[0], p[0] + 0.5 * t * d, end)]
        b["radius"] = [r, r, r]
        out[b["name"]] = round(outside, 1)
    return spec, out


STUB_DESCRIPTION = ("Validation arch {base} (anatomies/validation/arches) with its three great vessels cut to straight stubs "
                    "along their first direction, of their first radius, each ending {k} of its own radii outside the aortic "
                    "lumen: the roof of an arch as a phantom or a cropped scan shows it. Inlet: the descending aorta. "
                    "4 targets, 3 bifurcations. Written by anatomies/segmentation/make_arch_specs.py --stubs.")


# Stub arches of the segmentation-like set (training/guidewire_nav/segmentation_set.py): measured arches with their
# great vessels cut to stubs, (arch, stub length in radii). Chosen before any was extracted.
SEGMENTATION_STUBS = [("arch_type1", 1), ("arch_type2", 2)]


def write_stub(out, row, k, description):
    """Writes the stub arch of `row` (an ARCHES or VALIDATION_ARCHES entry) with stubs k radii long to `out`."""
    name, height, tb, tc, ts, _, _ = row
    spec, info = stub_arch(f"{name}_stub{k}", height, tb, tc, ts, k, description)
    (out / f"{name}_stub{k}.spec.json").write_text(spec_text(spec))
    print(f"{name}_stub{k}", json.dumps(info))


def spec_text(spec):
    """The committed specs' layout: one line per field, one line per branch."""
    head = ",\n".join(f"  {json.dumps(k)}: {json.dumps(spec[k])}" for k in ("name", "description", "units"))
    branches = ",\n".join("    " + json.dumps(b) for b in spec["branches"])
    return "{\n" + head + ',\n  "branches": [\n' + branches + "\n  ]\n}\n"


if __name__ == "__main__":
    import sys
    validation = "--validation" in sys.argv[1:]
    if "--stubs" in sys.argv[1:]:
        out = HERE.parent / "validation" / "arches"
        for row in VALIDATION_ARCHES:
            for k in (1, 2, 3):
                write_stub(out, row, k, STUB_DESCRIPTION.format(base=row[0], k=k))
        sys.exit(0)
    out = HERE.parent / "validation" / "arches" if validation else HERE
    out.mkdir(parents=True, exist_ok=True)
    if not validation:  # the segmentation set's stub arches, beside the arches they are cut from
        for base, k in SEGMENTATION_STUBS:
            desc = STUB_DESCRIPTION.replace("Validation arch {base} (anatomies/validation/arches)",
                                            "Arch {base} of the segmentation-like set").format(base=base, k=k)
            write_stub(out, next(a for a in ARCHES if a[0] == base), k, desc)
    for name, height, tb, tc, ts, kind, rule in VALIDATION_ARCHES if validation else ARCHES:
        desc = COMMON.format(type=kind, width=WIDTH, height=height, rule=rule)
        spec, info = arch(name, height, tb, tc, ts, desc)
        (out / f"{name}.spec.json").write_text(spec_text(spec))
        print(name, json.dumps(info))
