"""A segmentation-like test set made by the project (issue 35, item 2): no downloads.

    python -m guidewire_nav.segmentation_set --out DIR [--only NAME] [--voxel MM] [--arch-voxel MM]
                                             [--seed S] [--large] [--check]

Real vessel surfaces come from a label map (3D Slicer, ITK-SNAP, a script) through marching cubes:
a voxel staircase, speckle islands, either orientation, cut vessel ends, the odd non-manifold join,
metres or millimetres. This module makes such surfaces from trees whose ground truth is known:

1. truth: a generated centerline (schema guidewire-nav/centerline/1, mm): branches with points every
   <= 0.5 mm and the tube radius at each (`anatomy-gen` writes it beside the smooth mesh). Sources:
   the committed validation trees rca_validation and pl_validation (coronary-sized, r 0.8-2 mm) and
   the three aortic arches of anatomies/segmentation (Type I/II/III, r 4-14.4 mm, specs written by
   make_arch_specs.py; their truths are committed beside the specs). The frozen test trees are
   never used.
2. label map: voxel centres inside the union of spheres swept along every truth segment (radius
   linear along the segment), computed segment by segment in a narrow box around it; the free ends
   (inlet, targets) are cut flat at their end planes, as the generator's surface and a cropped scan
   are. Voxel 0.35 mm for coronary-sized trees, 0.5 mm for arches (defaults), box = tree + margin.
3. segmentation noise (seeded): a few percent of the boundary voxels flipped (inside <-> outside)
   and a few blobs of 2-4 voxels well away from the tree (speckle islands).
4. marching cubes: skimage.measure.marching_cubes (Lewiner) at level 0.5, run in slabs so that a
   1M-face tree fits in little memory; slab seams are welded exactly (shared vertices are bit-equal).
5. per-case corruptions, in this order:
     non_manifold  four small fins (a triangle on an existing edge: that edge gets 3 faces) and one
                   duplicated strip of ~12 faces (its edges get 4 faces), like welded touching parts
     open_ends     the faces within one voxel of each end plane (inlet and targets) removed: the cut
                   vessel ends of a cropped segmentation, open boundary loops
     flipped       every triangle's winding reversed (inward normals, negative signed volume)
     metres        coordinates / 1000
   label_noise and islands are listed too (every case has them). Marching cubes itself leaves a
   few non-manifold edges in some cases (pairs of coincident opposite triangles where noise voxels
   touch along an edge): real output, kept; the manifest's "measured" says what each file holds.
6. files: <name>.stl (binary), .ply (ASCII) or .obj, <name>.truth.json (the generator's truth, mm,
   copied byte for byte) and manifest.json for the whole set.

manifest.json is also an anatomy index (anatomies/index.json's format: {"anatomies": [{name, set,
mesh, truth, spec}]}, paths relative to the manifest's parent folder's parent, as the committed index's
are to the repository), so `bench-centerline --index DIR/manifest.json` runs on it. Each entry adds
scale_hint ("mm" or "m"), corruptions, targets, bifurcations, voxel_mm, faces, vertices, format,
seed, inlet_mm and the source truth/spec (repository-relative).

`--large` adds pl_large: pl_validation at 0.085 mm voxels, about 1M faces, for the speed benchmark
(issue 35 item 3). `--check` runs build/apps/centerline on every mesh (no --scale, no --inlet) and
prints its comparison with the truth (`compare_to_truth`, also used by the tests).

Deterministic: the same seed and voxel sizes give byte-identical files (one numpy Generator per
case, seeded from the set seed and the case name; fixed-format text output).
"""
import argparse
import json
import shutil
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
SEG = "anatomies/segmentation"
SOURCES = {
    "rca_validation": ("anatomies/validation/rca_validation/rca_validation.truth.json",
                       "anatomies/validation/rca_validation/rca_validation.spec.json", "coronary"),
    "pl_validation": ("anatomies/validation/pl_validation/pl_validation.truth.json",
                      "anatomies/validation/pl_validation/pl_validation.spec.json", "coronary"),
    **{f"arch_type{k}": (f"{SEG}/arch_type{k}.truth.json", f"{SEG}/arch_type{k}.spec.json", "arch") for k in (1, 2, 3)},
    # great vessels cut to stubs of 1 and 2 radii (make_arch_specs.SEGMENTATION_STUBS)
    **{n: (f"{SEG}/{n}.truth.json", f"{SEG}/{n}.spec.json", "arch") for n in ("arch_type1_stub1", "arch_type2_stub2")},
}
NOISE = ["label_noise", "islands"]
# name, source, format, corruptions (label noise and islands for all). Every corruption at least twice,
# each format three times, two cases in metres.
CASES = [
    ("rca_plain", "rca_validation", "stl", []),
    ("rca_flipped", "rca_validation", "ply", ["flipped"]),
    ("rca_open", "rca_validation", "obj", ["open_ends"]),
    ("pl_nonmanifold", "pl_validation", "stl", ["non_manifold"]),
    ("pl_open_flipped_m", "pl_validation", "ply", ["open_ends", "flipped", "metres"]),
    ("arch1_flipped", "arch_type1", "stl", ["flipped"]),
    ("arch2_open_nonmanifold", "arch_type2", "obj", ["non_manifold", "open_ends"]),
    ("arch3_nonmanifold_m", "arch_type3", "stl", ["non_manifold", "metres"]),
    ("arch3_open_flipped", "arch_type3", "ply", ["open_ends", "flipped"]),
    ("arch1_stub1_flipped", "arch_type1_stub1", "stl", ["flipped"]),
    ("arch2_stub2_open", "arch_type2_stub2", "obj", ["open_ends"]),
]
LARGE = ("pl_large", "pl_validation", "stl", [])
LARGE_VOXEL = 0.085
FLIP_FRACTION = 0.03       # of the boundary voxels, each side
ISLANDS = 4                # speckle blobs of 2-4 voxels per case
ISLAND_CLEARANCE_MM = 3.0  # from the tree's label


# ---------------------------------------------------------------- truth
def load_truth(path):
    """(truth dict, list of (points (n,3), radii (n,)) per branch)."""
    truth = json.loads(Path(path).read_text())
    return truth, truth_branches(truth)


def truth_branches(truth):
    return [(np.asarray(b["points"], float), np.asarray(b["radii"], float)) for b in truth["branches"]]


def free_ends(truth, branches):
    """(point, outward unit direction, radius) of every free end: the inlet and each target."""
    ends = []
    p, r = branches[truth["inlet"]["branch"]]
    ends.append((p[0], -np.asarray(truth["inlet"]["direction"], float), r[0]))
    for t in truth["targets"]:
        p, r = branches[t["branch"]]
        d = p[-1] - p[-2]
        ends.append((p[-1], d / np.linalg.norm(d), r[-1]))
    return ends


# ---------------------------------------------------------------- label map
def grid_for(branches, voxel, margin_mm):
    """Voxel-centre grid covering every tube plus a margin: (origin of voxel 0, shape)."""
    lo = np.min([np.min(p - r.max(), axis=0) for p, r in branches], axis=0) - margin_mm
    hi = np.max([np.max(p + r.max(), axis=0) for p, r in branches], axis=0) + margin_mm
    shape = tuple(int(n) for n in np.ceil((hi - lo) / voxel).astype(int) + 1)
    return lo, shape


def voxelise(branches, ends, origin, shape, voxel):
    """Boolean label: voxel centres within the union of swept spheres, free ends cut flat."""
    label = np.zeros(shape, bool)
    for points, radii in branches:
        for a, b, ra, rb in zip(points[:-1], points[1:], radii[:-1], radii[1:]):
            reach = max(ra, rb) + voxel
            i0 = np.maximum(np.floor((np.minimum(a, b) - reach - origin) / voxel).astype(int), 0)
            i1 = np.minimum(np.ceil((np.maximum(a, b) + reach - origin) / voxel).astype(int) + 1, shape)
            axes = [origin[k] + voxel * np.arange(i0[k], i1[k]) for k in range(3)]
            x = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
            e = b - a
            t = np.clip(((x - a) @ e) / max(e @ e, 1e-12), 0.0, 1.0)
            dist = np.linalg.norm(x - a - t[..., None] * e, axis=-1)
            label[i0[0]:i1[0], i0[1]:i1[1], i0[2]:i1[2]] |= dist <= ra + t * (rb - ra)
    for p, d, r in ends:  # a flat end: nothing past the end plane near the end
        reach = 1.6 * r + voxel
        i0 = np.maximum(np.floor((p - reach - origin) / voxel).astype(int), 0)
        i1 = np.minimum(np.ceil((p + reach - origin) / voxel).astype(int) + 1, shape)
        axes = [origin[k] + voxel * np.arange(i0[k], i1[k]) for k in range(3)]
        x = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1) - p
        beyond = (x @ d > 0) & (np.linalg.norm(x, axis=-1) < 1.6 * r)
        label[i0[0]:i1[0], i0[1]:i1[1], i0[2]:i1[2]] &= ~beyond
    return label


def boundary(label):
    """(inside voxels with an outside 6-neighbour, outside voxels with an inside 6-neighbour)."""
    grown, shrunk = label.copy(), label.copy()
    for axis in range(3):
        lo = tuple(slice(None, -1) if k == axis else slice(None) for k in range(3))
        hi = tuple(slice(1, None) if k == axis else slice(None) for k in range(3))
        grown[hi] |= label[lo]
        grown[lo] |= label[hi]
        shrunk[hi] &= label[lo]
        shrunk[lo] &= label[hi]
    return label & ~shrunk, grown & ~label


def add_label_noise(label, rng):
    """Flip FLIP_FRACTION of the inner and of the outer boundary voxels; returns (inner, outer) counts."""
    inner, outer = boundary(label)
    counts = []
    for mask, value in ((inner, False), (outer, True)):
        idx = np.flatnonzero(mask)
        pick = idx[rng.random(idx.size) < FLIP_FRACTION]
        label.flat[pick] = value
        counts.append(int(pick.size))
    return counts


def add_islands(label, rng, voxel):
    """ISLANDS blobs of 2-4 face-connected voxels, each >= ISLAND_CLEARANCE_MM from any label voxel."""
    k = int(np.ceil(ISLAND_CLEARANCE_MM / voxel))
    steps = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]])
    shape = np.array(label.shape)
    placed = 0
    while placed < ISLANDS:
        seed = rng.integers(k + 2, shape - k - 2)
        box = tuple(slice(s - k - 2, s + k + 3) for s in seed)
        if label[box].any():
            continue
        blob = [seed]
        for _ in range(int(rng.integers(1, 4))):
            blob.append(blob[int(rng.integers(len(blob)))] + steps[int(rng.integers(6))])
        for v in blob:
            label[tuple(v)] = True
        placed += 1
    return placed


# ---------------------------------------------------------------- marching cubes
def marching_cubes(label, origin, voxel, slab=64):
    """Outward-oriented triangle surface (vertices in mm, faces) of a label map, slab by slab.

    Each slab of `slab` voxel layers overlaps the next by one layer; vertices on a seam come out
    bit-equal from both sides (binary data at level 0.5: edge midpoints), so np.unique welds them."""
    from skimage.measure import marching_cubes as skimage_mc

    nx, ny, nz = label.shape
    verts, faces, count = [], [], 0
    for start in range(0, nx + 1, slab):  # layers start..start+slab of the label padded by one empty voxel
        block = np.zeros((min(slab + 1, nx + 2 - start), ny + 2, nz + 2), np.float32)
        lo, hi = max(start - 1, 0), min(start + slab, nx)
        block[lo + 1 - start:hi + 1 - start, 1:-1, 1:-1] = label[lo:hi]
        if not block.any():
            continue
        v, f, _, _ = skimage_mc(block, level=0.5)
        v = v.astype(np.float64)
        v[:, 0] += start
        verts.append(v)
        faces.append(f + count)
        count += len(v)
    verts = np.concatenate(verts)
    unique, inverse = np.unique(verts, axis=0, return_inverse=True)
    faces = inverse.reshape(-1)[np.concatenate(faces)]
    # Index units of the padded grid -> mm (voxel 1 of the padded grid is voxel 0 of `label`).
    v, f = origin + (unique - 1.0) * voxel, faces.astype(np.int64)
    if signed_volume(v, f) < 0:  # skimage winds the label's surface inwards: turn it outwards
        f = f[:, [0, 2, 1]]
    return v, f


def signed_volume(v, f):
    return float(np.sum(np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]]))) / 6.0)


# ---------------------------------------------------------------- corruptions
def face_normals(v, f):
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)


def add_non_manifold(v, f, rng, voxel):
    """Four fins (a new triangle on an existing edge, sticking out 0.7 voxel) and one duplicated strip
    (a face and its neighbours, ~12 faces, added again on the same vertices)."""
    normals = face_normals(v, f)
    fins = rng.choice(len(f), size=4, replace=False)
    a, b = f[fins, 0], f[fins, 1]
    tips = 0.5 * (v[a] + v[b]) + 0.7 * voxel * normals[fins]
    fin_faces = np.stack([b, a, len(v) + np.arange(len(fins))], axis=1)
    centre = f[int(rng.integers(len(f)))]
    ring = np.flatnonzero(np.isin(f, centre).any(axis=1))
    strip = np.flatnonzero(np.isin(f, np.unique(f[ring])).any(axis=1))[:12]
    return np.concatenate([v, tips]), np.concatenate([f, fin_faces, f[strip]])


def open_ends(v, f, ends, voxel):
    """Remove, at each end (inlet, targets), the faces whose centroid lies less than 1.5 voxels before
    the end plane or past it: the largest edge-connected patch of them (the cap and the rim of wall
    behind it; a staircase face that strays across the threshold elsewhere would make a pinhole). Then
    drop the few scraps the cut leaves (a noise bump on the flat end): pieces with an open boundary
    and under 100 faces."""
    c = v[f].mean(axis=1)
    remove = np.zeros(len(f), bool)
    for p, d, r in ends:
        x = c - p
        axial = x @ d
        lateral = np.linalg.norm(x - axial[:, None] * d, axis=1)
        near = np.flatnonzero((axial > -1.5 * voxel) & (axial < r) & (lateral < 1.6 * r))
        patch = face_patches(f[near])
        remove[near[patch == np.argmax(np.bincount(patch))]] = True
    v, f = compact(v, f[~remove])
    edges, count = edge_counts(f)
    piece = pieces_of(edges, len(v))
    open_pieces = np.unique(piece[edges[count == 1].ravel()])
    sizes = np.bincount(piece[f[:, 0]], minlength=len(v))
    scraps = open_pieces[sizes[open_pieces] < 100]
    return compact(v, f[~np.isin(piece[f[:, 0]], scraps)])


def face_patches(f):
    """Label of the edge-connected patch of each face."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, edge_id = np.unique(edges, axis=0, return_inverse=True)
    face_id = np.tile(np.arange(len(f)), 3)
    n = len(f) + int(edge_id.max()) + 1  # a graph of faces and edges: face i -- edge j when j is a side of i
    graph = coo_matrix((np.ones(len(face_id)), (face_id, len(f) + edge_id.reshape(-1))), shape=(n, n))
    return connected_components(graph, directed=False)[1][:len(f)]


def compact(v, f):
    used, inverse = np.unique(f, return_inverse=True)
    return v[used], inverse.reshape(f.shape)


# ---------------------------------------------------------------- inspecting and reading back
def read_mesh(path):
    """(vertices, faces) of a file written above; STL corners are welded where bit-equal."""
    path = Path(path)
    if path.suffix == ".stl":
        data = path.read_bytes()
        n = struct.unpack("<I", data[80:84])[0]
        rec = np.frombuffer(data, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")], count=n, offset=84)
        v, f = np.unique(rec["v"].reshape(-1, 3).astype(np.float64), axis=0, return_inverse=True)
        return v, f.reshape(-1, 3)
    lines = path.read_text().splitlines()
    if path.suffix == ".ply":
        nv = int(next(l for l in lines if l.startswith("element vertex")).split()[-1])
        start = lines.index("end_header") + 1
        v = np.array([l.split() for l in lines[start:start + nv]], float)
        f = np.array([l.split()[1:4] for l in lines[start + nv:]], np.int64)
        return v, f
    v = np.array([l.split()[1:4] for l in lines if l.startswith("v ")], float)
    f = np.array([l.split()[1:4] for l in lines if l.startswith("f ")], np.int64) - 1
    return v, f


def edge_counts(f):
    """(unique undirected edges (m,2), faces per edge (m,))."""
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    return np.unique(edges, axis=0, return_counts=True)


def pieces_of(edges, n):
    """Connected-component label of each of n vertices joined by edges (scipy comes with scikit-image)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    return connected_components(graph, directed=False)[1]


def boundary_loops(f):
    """Number of connected chains of boundary edges (edges with one face): the holes (a fin's two free
    edges make one too)."""
    edges, count = edge_counts(f)
    free = edges[count == 1]
    if len(free) == 0:
        return 0
    labels = pieces_of(free, int(f.max()) + 1)
    return len(np.unique(labels[np.unique(free)]))


def mesh_stats(v, f):
    """Faces, boundary edges (1 face), non-manifold edges (3+ faces), connected pieces, signed volume
    (the sign says the orientation of a closed surface) and the largest bounding-box side."""
    edges, per_edge = edge_counts(f)
    pieces = len(np.unique(pieces_of(edges, len(v))[np.unique(f)]))
    volume = signed_volume(v, f)
    return {"faces": int(len(f)), "boundary_edges": int(np.sum(per_edge == 1)),
            "non_manifold_edges": int(np.sum(per_edge > 2)), "pieces": pieces, "signed_volume": volume,
            "extent": float(np.max(v.max(axis=0) - v.min(axis=0)))}


# ---------------------------------------------------------------- writers (fixed formats: deterministic)
def write_stl(path, v, f):
    tri = v[f].astype(np.float32)
    n = face_normals(v, f).astype(np.float32)
    rec = np.zeros(len(f), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    rec["n"], rec["v"] = n, tri
    with open(path, "wb") as out:
        out.write(b"guidewire-nav segmentation-like set (binary STL)".ljust(80, b" "))
        out.write(struct.pack("<I", len(f)))
        out.write(rec.tobytes())


def vertex_lines(v, fmt):
    return "\n".join(fmt % tuple(p) for p in v) + "\n"


def write_ply(path, v, f, coord_fmt):
    head = (f"ply\nformat ascii 1.0\ncomment guidewire-nav segmentation-like set\nelement vertex {len(v)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n")
    body = vertex_lines(v, f"{coord_fmt} {coord_fmt} {coord_fmt}")
    body += "\n".join("3 %d %d %d" % tuple(t) for t in f) + "\n"
    Path(path).write_text(head + body)


def write_obj(path, v, f, coord_fmt):
    text = "# guidewire-nav segmentation-like set\n" + vertex_lines(v, f"v {coord_fmt} {coord_fmt} {coord_fmt}")
    text += "\n".join("f %d %d %d" % tuple(t + 1) for t in f) + "\n"
    Path(path).write_text(text)


# ---------------------------------------------------------------- one case
def case_seed(seed, name):
    return [seed, zlib.crc32(name.encode())]


def make_case(name, source, fmt, corruptions, voxel, out_dir, seed):
    truth_path, spec_path, _ = SOURCES[source]
    truth, branches = load_truth(REPO / truth_path)
    ends = free_ends(truth, branches)
    rng = np.random.default_rng(case_seed(seed, name))

    margin = ISLAND_CLEARANCE_MM + 6 * voxel
    origin, shape = grid_for(branches, voxel, margin)
    label = voxelise(branches, ends, origin, shape, voxel)
    flipped_in, flipped_out = add_label_noise(label, rng)
    islands = add_islands(label, rng, voxel)
    v, f = marching_cubes(label, origin, voxel)

    if "non_manifold" in corruptions:
        v, f = add_non_manifold(v, f, rng, voxel)
    if "open_ends" in corruptions:
        v, f = open_ends(v, f, ends, voxel)
    if "flipped" in corruptions:
        f = f[:, [0, 2, 1]]
    metres = "metres" in corruptions
    if metres:
        v = v / 1000.0
    coord_fmt = "%.9f" if metres else "%.6f"

    mesh_file = f"{name}.{fmt}"
    {"stl": lambda: write_stl(out_dir / mesh_file, v, f),
     "ply": lambda: write_ply(out_dir / mesh_file, v, f, coord_fmt),
     "obj": lambda: write_obj(out_dir / mesh_file, v, f, coord_fmt)}[fmt]()
    shutil.copyfile(REPO / truth_path, out_dir / f"{name}.truth.json")
    stats = mesh_stats(v, f)
    prefix = out_dir.name
    return {
        "name": name, "set": "segmentation",
        "mesh": f"{prefix}/{mesh_file}", "truth": f"{prefix}/{name}.truth.json", "spec": "",
        "source_truth": truth_path, "source_spec": spec_path,
        "format": {"stl": "binary STL", "ply": "ASCII PLY", "obj": "OBJ"}[fmt],
        "scale_hint": "m" if metres else "mm",
        "corruptions": NOISE + corruptions,
        "targets": len(truth["targets"]), "bifurcations": len(truth["bifurcations"]),
        "voxel_mm": voxel, "faces": int(len(f)), "vertices": int(len(v)),
        "grid": list(shape), "flipped_voxels": flipped_in + flipped_out, "islands": islands,
        "inlet_mm": truth["inlet"]["position"], "seed": seed,
        "measured": {k: stats[k] for k in ("boundary_edges", "non_manifold_edges", "pieces")} |
                    {"boundary_loops": boundary_loops(f), "orientation": "outward" if stats["signed_volume"] > 0 else "inward",
                     "extent": round(stats["extent"], 6)},
    }


def build_set(out_dir, voxel=0.35, arch_voxel=0.5, only=None, seed=35, large=False, log=print):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cases = CASES + ([LARGE] if large else [])
    entries = []
    for name, source, fmt, corruptions in cases:
        if only and name != only:
            continue
        size = SOURCES[source][2]
        vx = LARGE_VOXEL if name == LARGE[0] else (arch_voxel if size == "arch" else voxel)
        t0 = time.perf_counter()
        entry = make_case(name, source, fmt, corruptions, vx, out_dir, seed)
        log(f"{name}: {entry['format']}, {entry['scale_hint']}, {', '.join(entry['corruptions'])}; voxel {vx} mm, "
            f"{entry['faces']} faces, {entry['targets']} targets ({time.perf_counter() - t0:.1f} s)")
        entries.append(entry)
    if only and not entries:
        raise SystemExit(f"no case named {only}; cases: {', '.join(c[0] for c in cases)}")
    manifest = {"schema": "guidewire-nav/segmentation-set/1", "seed": seed,
                "note": "also an anatomy index: paths are relative to this file's parent folder's parent",
                "anatomies": entries}
    (out_dir / "manifest.json").write_text(json.dumps(manifest, indent=2) + "\n")
    return manifest


# ---------------------------------------------------------------- comparison with the truth
def nearest_on_truth(branches, x):
    """For points x (n,3): distance to the nearest truth segment and the truth radius there."""
    best_d = np.full(len(x), np.inf)
    best_r = np.zeros(len(x))
    for p, r in branches:
        a, e = p[:-1], p[1:] - p[:-1]
        for lo in range(0, len(x), 256):
            q = x[lo:lo + 256, None, :]
            t = np.clip(np.einsum("nsk,sk->ns", q - a, e) / np.maximum(np.einsum("sk,sk->s", e, e), 1e-300), 0, 1)
            d = np.linalg.norm(q - a - t[..., None] * e, axis=-1)
            j = np.argmin(d, axis=1)
            dj = d[np.arange(len(j)), j]
            rj = (1 - t[np.arange(len(j)), j]) * r[:-1][j] + t[np.arange(len(j)), j] * r[1:][j]
            better = dj < best_d[lo:lo + 256]
            best_d[lo:lo + 256][better] = dj[better]
            best_r[lo:lo + 256][better] = rj[better]
    return best_d, best_r


def compare_to_truth(extracted, truth):
    """Extracted centerline JSON vs the truth (both dicts, mm), in units of the local true radius.

    targets/bifurcations: counts (the inlet choice does not change them); mean_distance: mean over the
    extracted points (a child's shared first point once) of the distance to the nearest truth segment
    / the truth radius there; bifurcation_offset: max over true bifurcations of the distance to the
    nearest extracted one / the dividing (parent) branch's radius at its end; terminal_offset: max
    over true terminals (inlet, targets) of the distance to its own nearest extracted terminal / its radius."""
    tb = truth_branches(truth)
    pts = np.concatenate([np.asarray(b["points"], float)[(1 if b["parent"] >= 0 else 0):]
                          for b in extracted["branches"]])
    d, r = nearest_on_truth(tb, pts)
    ex_bif = np.array([b["position"] for b in extracted["bifurcations"]], float).reshape(-1, 3)
    bif = 0.0
    for b in truth["bifurcations"]:
        radius = tb[b["parent"]][1][-1]
        dist = np.min(np.linalg.norm(ex_bif - b["position"], axis=1)) if len(ex_bif) else np.inf
        bif = max(bif, dist / radius)
    ex_term = [extracted["inlet"]["position"]] + [t["position"] for t in extracted["targets"]]
    true_term = [(truth["inlet"]["position"], truth["inlet"]["radius"])] + \
                [(t["position"], t["radius"]) for t in truth["targets"]]
    taken, term = set(), 0.0
    for pos, radius in true_term:
        dists = [np.linalg.norm(np.subtract(q, pos)) if i not in taken else np.inf for i, q in enumerate(ex_term)]
        i = int(np.argmin(dists))
        taken.add(i)
        term = max(term, dists[i] / radius)
    return {"targets": len(extracted["targets"]), "true_targets": len(truth["targets"]),
            "bifurcations": len(extracted["bifurcations"]), "true_bifurcations": len(truth["bifurcations"]),
            "points": int(len(pts)), "mean_distance": float(np.mean(d / r)), "p95_distance": float(np.percentile(d / r, 95)),
            "bifurcation_offset": float(bif), "terminal_offset": float(term)}


def accurate(c):
    """The issue's bar: the right tree (equal counts, and every true terminal has its own extracted one
    within 2 radii, as bench-centerline's same_topology), mean error <= 5% of the radius, bifurcations
    within 0.5 radius."""
    return (c["targets"] == c["true_targets"] and c["bifurcations"] == c["true_bifurcations"]
            and c["terminal_offset"] <= 2.0 and c["mean_distance"] <= 0.05 and c["bifurcation_offset"] <= 0.5)


def run_centerline(mesh, out_json, timeout=300):
    """`centerline --anatomy MESH --no-cache --out OUT` as a user would run it (no --scale, no --inlet).
    Returns (returncode, stderr, seconds); a run past `timeout` seconds is killed and returns 124."""
    from guidewire_nav import app_path

    t0 = time.perf_counter()
    try:
        p = subprocess.run([str(app_path("centerline")), "--anatomy", str(mesh), "--no-cache", "--out", str(out_json)],
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired as e:
        err = e.stderr.decode() if isinstance(e.stderr, bytes) else (e.stderr or "")
        return 124, (err + f"\nkilled after {timeout} s").strip(), time.perf_counter() - t0
    return p.returncode, p.stderr.strip(), time.perf_counter() - t0


def check_set(manifest_path, log=print):
    manifest_path = Path(manifest_path)
    root = manifest_path.resolve().parent.parent
    ok = True
    for e in json.loads(manifest_path.read_text())["anatomies"]:
        out = manifest_path.parent / f"{e['name']}.extracted.json"
        rc, err, sec = run_centerline(root / e["mesh"], out)
        if rc != 0:
            log(f"{e['name']}: FAIL (exit {rc}, {sec:.1f} s): {err.splitlines()[-1] if err else ''}")
            ok = False
            continue
        c = compare_to_truth(json.loads(out.read_text()), json.loads((root / e["truth"]).read_text()))
        good = accurate(c)
        ok &= good
        log(f"{e['name']}: {'pass' if good else 'FAIL'} ({sec:.1f} s) targets {c['targets']}/{c['true_targets']}, "
            f"bifurcations {c['bifurcations']}/{c['true_bifurcations']}, mean distance {c['mean_distance']:.3f} r, "
            f"bifurcation offset {c['bifurcation_offset']:.2f} r, terminal offset {c['terminal_offset']:.2f} r"
            + (f"; stderr: {err}" if err else ""))
    return ok


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="output folder (mesh, truth and manifest.json)")
    ap.add_argument("--only", help="make only this case")
    ap.add_argument("--voxel", type=float, default=0.35, help="voxel of the coronary-sized trees, mm")
    ap.add_argument("--arch-voxel", type=float, default=0.5, help="voxel of the aortic arches, mm")
    ap.add_argument("--seed", type=int, default=35, help="set seed (each case's generator: this and its name)")
    ap.add_argument("--large", action="store_true", help=f"also pl_large (~1M faces, voxel {LARGE_VOXEL} mm)")
    ap.add_argument("--check", action="store_true", help="run build/apps/centerline on every mesh and compare")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    build_set(args.out, args.voxel, args.arch_voxel, args.only, args.seed, args.large)
    print(f"set written to {args.out} in {time.perf_counter() - t0:.1f} s")
    if args.check:
        return 0 if check_set(Path(args.out) / "manifest.json") else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
