"""The segmentation-like set (issue 35 item 2): it is made deterministically, its corruptions are
really in the files, its arches are the arch types they claim, and `centerline` recovers the true tree
from every mesh.

The end-to-end part is `test_segmentation_mesh_gives_the_right_tree[<case>]` and
`test_segmentation_mesh_meets_the_accuracy_bar[<case>]` (select them with `-k segmentation_mesh`). It runs `centerline --anatomy MESH --no-cache` exactly as a user
would: no --scale (metres must be detected), no --inlet (the counts and distances compared do not
depend on which terminal is the inlet). The bar is the issue's: same number of targets and
bifurcations as the truth, mean distance of the extracted points to the true centerline <= 5% of the
local true radius, every true bifurcation within 0.5 of its parent's radius of an extracted one; and,
as bench-centerline's same_topology, every true terminal with its own extracted terminal within 2 of its
radii (equal counts alone pass a tree that lost a branch and grew a spur).
"""
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import guidewire_nav
from guidewire_nav import segmentation_set as seg

pytest.importorskip("skimage")

REPO = Path(__file__).resolve().parents[2]
VOXEL, ARCH_VOXEL = 0.4, 0.6  # the coarse ends of the ranges, to keep the test quick


@pytest.fixture(scope="module")
def seg_set(tmp_path_factory):
    out = tmp_path_factory.mktemp("segmentation") / "set"
    manifest = seg.build_set(out, voxel=VOXEL, arch_voxel=ARCH_VOXEL, log=lambda *_: None)
    return out / "manifest.json", {e["name"]: e for e in manifest["anatomies"]}


def test_set_is_deterministic_and_listed(seg_set, tmp_path):
    manifest_path, entries = seg_set
    assert sorted(entries) == sorted(c[0] for c in seg.CASES)
    again = seg.build_set(tmp_path / "set", voxel=VOXEL, arch_voxel=ARCH_VOXEL, only="pl_open_flipped_m",
                          log=lambda *_: None)["anatomies"][0]
    assert again == entries["pl_open_flipped_m"]
    for suffix in (".ply", ".truth.json"):
        assert (tmp_path / "set" / f"pl_open_flipped_m{suffix}").read_bytes() == \
               (manifest_path.parent / f"pl_open_flipped_m{suffix}").read_bytes()
    # Also an anatomy index: name, set, mesh, truth resolve from the manifest's parent's parent.
    root = manifest_path.parent.parent
    for e in entries.values():
        assert (root / e["mesh"]).is_file() and (root / e["truth"]).is_file()
        assert set(e) >= {"name", "set", "mesh", "truth", "spec", "scale_hint", "corruptions", "targets",
                          "bifurcations", "voxel_mm", "faces"}


def test_set_covers_every_corruption_in_every_format(seg_set):
    _, entries = seg_set
    corruptions = {c for e in entries.values() for c in e["corruptions"]}
    assert corruptions == {"label_noise", "islands", "non_manifold", "open_ends", "flipped", "metres"}
    assert {e["format"] for e in entries.values()} == {"binary STL", "ASCII PLY", "OBJ"}
    assert sum(e["scale_hint"] == "m" for e in entries.values()) == 2
    assert {e["source_truth"].split("/")[-1] for e in entries.values()} == {
        "rca_validation.truth.json", "pl_validation.truth.json", "arch_type1.truth.json",
        "arch_type2.truth.json", "arch_type3.truth.json", "arch_type1_stub1.truth.json", "arch_type2_stub2.truth.json"}
    assert not any("anatomies/test/" in e["source_truth"] for e in entries.values())  # frozen test rows


def test_corruptions_are_in_the_files(seg_set):
    manifest_path, entries = seg_set
    seen = set()
    for name, e in entries.items():
        v, f = seg.read_mesh(manifest_path.parent.parent / e["mesh"])
        s = seg.mesh_stats(v, f)
        has = set(e["corruptions"])
        assert s["faces"] == e["faces"], name
        assert s["pieces"] > 1, f"{name}: the speckle islands are separate pieces"
        assert (s["signed_volume"] < 0) == ("flipped" in has), f"{name}: signed volume {s['signed_volume']}"
        assert e["measured"]["non_manifold_edges"] == s["non_manifold_edges"], name
        if "non_manifold" in has:  # 4 fins (1 edge each) and a duplicated strip (>= 12 edges)
            assert s["non_manifold_edges"] >= 16, name
        else:  # marching cubes' own coincident opposite triangles, a few at most
            assert s["non_manifold_edges"] <= 12, name
        if "open_ends" in has:
            assert s["boundary_edges"] > 0, name
        elif "non_manifold" not in has:  # fins have free edges; otherwise the surface is closed
            assert s["boundary_edges"] == 0, name
        # Units by extent: coronary-sized trees are ~80 mm across, arches ~200 mm; in metres < 1.
        assert (s["extent"] < 1.0) == ("metres" in has), f"{name}: extent {s['extent']}"
        assert 50 < s["extent"] * (1000 if "metres" in has else 1) < 300, name
        if s["signed_volume"] < 0:
            seen.add("inward")
        seen.update(k for k in ("boundary_edges", "non_manifold_edges") if s[k] > 0)
        if s["extent"] < 1.0:
            seen.add("metres")
    assert seen == {"inward", "boundary_edges", "non_manifold_edges", "metres"}


def test_open_ends_leave_one_hole_per_end(seg_set):
    """Each cut end is one open boundary loop (a cropped vessel), not a ragged sieve."""
    manifest_path, entries = seg_set
    for name, e in entries.items():
        if "open_ends" not in e["corruptions"] or "non_manifold" in e["corruptions"]:
            continue
        v, f = seg.read_mesh(manifest_path.parent.parent / e["mesh"])
        assert seg.boundary_loops(f) == e["targets"] + 1, name


@pytest.mark.parametrize("arch, low, high", [("arch_type1", 0.0, 1.0), ("arch_type2", 1.0, 2.0),
                                              ("arch_type3", 2.0, 10.0)])
def test_arch_types_by_brachiocephalic_drop(arch, low, high):
    """Measured on the generator's truth: the drop from the top of the arch's outer curvature to where
    the brachiocephalic centreline leaves the aortic lumen, in left-common-carotid diameters."""
    truth = json.loads((REPO / "anatomies/segmentation" / f"{arch}.truth.json").read_text())
    spec = json.loads((REPO / "anatomies/segmentation" / f"{arch}.spec.json").read_text())
    assert truth["inlet"]["radius"] == pytest.approx(10.0)  # the descending aorta is the inlet
    assert len(truth["targets"]) == 4 and len(truth["bifurcations"]) == 3
    branches = seg.truth_branches(truth)
    aorta = np.concatenate([p for p, r in branches if r.min() > 9.0])
    aorta_r = np.concatenate([r for p, r in branches if r.min() > 9.0])
    apex = np.max(aorta[:, 2] + aorta_r)
    bct = next(p for p, r in branches if 5.5 < r[-1] < 6.5)
    dist = np.linalg.norm(bct[:, None] - aorta[None], axis=2) - aorta_r[None]
    origin_z = bct[np.argmax(dist.min(axis=1) >= 0), 2]
    cca_diameter = 2 * spec["branches"][2]["radius"][0]
    assert low < (apex - origin_z) / cca_diameter < high


def test_arch_truths_are_the_generators(tmp_path):
    gen = guidewire_nav.app_path("anatomy-gen")
    if not gen.is_file():
        pytest.skip(f"anatomy-gen not built ({gen}); set GW_BUILD_DIR")
    for name in ("arch_type1", "arch_type2", "arch_type3", "arch_type1_stub1", "arch_type2_stub2"):
        spec = REPO / f"anatomies/segmentation/{name}.spec.json"
        subprocess.run([str(gen), "--spec", str(spec), "--out", str(tmp_path)], check=True, capture_output=True)
        assert (tmp_path / f"{name}.truth.json").read_bytes() == \
               (REPO / f"anatomies/segmentation/{name}.truth.json").read_bytes()


# The accuracy bar (mean <= 5% of the radius, bifurcations within 0.5 radius) is met on every
# mesh of the set at these coarse voxels (0.4 / 0.6 mm; results/segmentation/README.md). The arches
# met it once MCF got a surface fine enough for their thin great vessels
# (CenterlineOptions::edges_around_thinnest) and two side branches of the aorta stopped merging
# unless their openings overlap (skeleton_tree.hpp); before, the arches at 0.6 mm missed it and the
# Type III arch lost a bifurcation.

@pytest.fixture(scope="module")
def extracted(seg_set, tmp_path_factory):
    """centerline on every mesh, once: {case: (return code, stderr, extracted JSON or None, truth)}."""
    centerline = guidewire_nav.app_path("centerline")
    if not centerline.is_file():
        pytest.skip(f"centerline not built ({centerline}); set GW_BUILD_DIR")
    manifest_path, entries = seg_set
    root = manifest_path.parent.parent
    out_dir = tmp_path_factory.mktemp("extracted")
    results = {}
    for case, e in entries.items():
        out = out_dir / f"{case}.json"
        rc, err, _ = seg.run_centerline(root / e["mesh"], out, timeout=120)  # issue 35: 1M faces in 10 s
        truth = json.loads((root / e["truth"]).read_text())
        results[case] = (rc, err, json.loads(out.read_text()) if rc == 0 else None, truth)
    return results


# A known limitation (centerline/README.md "Great vessels cut to stubs"): on a closed voxel surface the stubs' cut
# ends are terraces, not the flat disks flat_ends.hpp finds, and MCF contracts stubs of one radius: the aorta alone.
# Both stub cases were added before either was extracted; the open one passes (its ends are capped holes).
STUB_LIMIT = pytest.mark.xfail(strict=True, reason="stubs on a closed voxel surface: ends not found")
CASES = [pytest.param(c[0], marks=STUB_LIMIT) if c[0] == "arch1_stub1_flipped" else c[0] for c in seg.CASES]


@pytest.mark.parametrize("case", CASES)
def test_segmentation_mesh_gives_the_right_tree(seg_set, extracted, case):
    """Every mesh is taken in without a refusal, its repairs are reported, and the tree is the truth's:
    each true end has its own extracted end within 2 radii, as many targets, as many bifurcations, and no branch far off its vessel (mean <= 0.25 r)."""
    _, entries = seg_set
    rc, err, graph, truth = extracted[case]
    assert rc == 0, f"{case}: centerline failed: {err}"
    c = seg.compare_to_truth(graph, truth)
    report = f"{case}: {c}; stderr: {err}"
    assert c["targets"] == c["true_targets"], report
    assert c["terminal_offset"] <= 2.0, report
    assert c["bifurcations"] == c["true_bifurcations"], report
    assert c["mean_distance"] <= 0.25, report
    assert "repaired:" in err, report  # every mesh of the set has something to repair, and says so
    if "metres" in entries[case]["corruptions"]:
        assert "read as metres" in err, f"{case}: the scaling from metres is not reported on stderr: {err}"


@pytest.mark.parametrize("case", CASES)
def test_segmentation_mesh_meets_the_accuracy_bar(extracted, case):
    """The issue's bar: mean distance <= 5% of the local true radius, every true bifurcation within 0.5
    of its parent's radius of an extracted one, on top of the right tree."""
    rc, err, graph, truth = extracted[case]
    assert rc == 0, err
    c = seg.compare_to_truth(graph, truth)
    assert seg.accurate(c), f"{case}: {c}"


def test_no_stub_target_where_a_junction_was_recentred(tmp_path):
    """At 0.35 mm the pl tree with open, flipped ends in metres left a skeleton spur at a junction
    that survived the spur pruning but shrank to 0.8 mm once the junction was re-centred onto the
    vessel axes: a sixth target on a 5-target tree. A terminal stub shorter than spur_factor (2) of
    its radii, at a junction that keeps two other children, is dropped: the right tree."""
    centerline = guidewire_nav.app_path("centerline")
    if not centerline.is_file():
        pytest.skip(f"centerline not built ({centerline}); set GW_BUILD_DIR")
    e = seg.build_set(tmp_path / "set", voxel=0.35, only="pl_open_flipped_m", log=lambda *_: None)["anatomies"][0]
    out = tmp_path / "extracted.json"
    rc, err, _ = seg.run_centerline(tmp_path / e["mesh"], out, timeout=120)
    assert rc == 0, err
    c = seg.compare_to_truth(json.loads(out.read_text()), json.loads((tmp_path / e["truth"]).read_text()))
    assert (c["targets"], c["bifurcations"]) == (c["true_targets"], c["true_bifurcations"]) == (5, 4), c
    assert c["terminal_offset"] <= 2.0, c


@pytest.mark.parametrize("case", ["pl_open_flipped_m", "arch2_open_nonmanifold"])
def test_segmentation_mesh_navigates(seg_set, case, tmp_path):
    """Acceptance (issue 35 item 6): a repaired segmentation surface runs `navigate --target all` end to
    end, every target an episode with an outcome, no refusal. The inlet comes from the truth sidecar
    beside the mesh (as for the shipped anatomies); the arch gets the aortic wire. One cut-open, inward,
    metre-scaled coronary-sized tree and one cut-open, non-manifold arch (the full set's run is in
    results/segmentation/README.md)."""
    navigate = guidewire_nav.app_path("navigate")
    if not navigate.is_file():
        pytest.skip(f"navigate not built ({navigate}); set GW_BUILD_DIR")
    manifest_path, entries = seg_set
    e = entries[case]
    cmd = [str(navigate), "--anatomy", str(manifest_path.parent.parent / e["mesh"]), "--target", "all",
           "--episodes", "1", "--threads", "2", "--json", "--no-cache", "--controller", "scripted-omega"]
    if case.startswith("arch"):
        cmd += ["--wire", str(REPO / "engine/wire/aortic_035_angled.json")]
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, f"{case}: navigate refused: {run.stderr}"
    summary = json.loads(run.stdout)
    assert summary["episodes"] == e["targets"]
    assert sum(summary["outcomes"].values()) == e["targets"]
    assert summary["outcomes"].get("diverged", 0) == 0, summary["outcomes"]
    assert summary["intake"]["repairs"], summary["intake"]
    assert summary["centerline"]["targets"] == e["targets"]
