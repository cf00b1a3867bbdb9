"""gw-anatomy-pool: the seeded anatomy distribution (issue 64 item 1) and the server loading a pool's index."""

import json
import subprocess

import numpy as np
import pytest

import guidewire_nav
from guidewire_nav import anatomy_pool


def specs(tmp_path, seed, count, kinds="coronary,arch", options=(), name=None):
    out = tmp_path / (name or f"pool_{seed}")
    assert anatomy_pool.main(["--out", str(out), "--count", str(count), "--seed", str(seed), "--kinds", kinds,
                              "--specs-only", *options]) == 0
    index = json.loads((out / "index.json").read_text())["anatomies"]
    return out, [json.loads((out.parent / e["spec"]).read_text()) for e in index], index


def test_same_seed_same_specs_and_other_seeds_differ(tmp_path):
    _, a, _ = specs(tmp_path / "a", 7, 6)
    _, b, _ = specs(tmp_path / "b", 7, 6)
    _, c, _ = specs(tmp_path / "c", 8, 6)
    assert a == b
    assert [s["branches"] for s in a] != [s["branches"] for s in c]
    # sample i depends on (seed, i) only: a longer pool starts with the shorter one
    _, longer, _ = specs(tmp_path / "d", 7, 9)
    assert longer[:6] == a


def test_coronary_trees_cover_what_the_issue_asks_for(tmp_path):
    _, trees, index = specs(tmp_path, 3, 60, kinds="coronary")
    assert {e["set"] for e in index} == {"coronary"}
    radii = [r for t in trees for b in t["branches"] for r in b["radius"]]
    assert 0.3 <= min(radii) < 0.45 and max(radii) <= 2.2
    targets = [len(t["branches"]) - 1 for t in trees]
    assert min(targets) >= 2 and max(targets) <= anatomy_pool.MAX_TARGETS
    children = [sum(1 for b in t["branches"] if b.get("parent") == 0) for t in trees]
    assert 2 in children and 3 in children  # two-way forks and trifurcations at the stem
    assert any("deformation" in t for t in trees) and not all("deformation" in t for t in trees)
    for t in trees:  # every distal end narrower than its branch's start
        for b in t["branches"][1:]:
            assert b["radius"][-1] < b["radius"][0]


def test_arches_keep_the_great_vessels_in_order(tmp_path):
    _, arches, _ = specs(tmp_path, 5, 4, kinds="arch")
    for a in arches:
        names = [b["name"] for b in a["branches"]]
        assert names == ["aorta_descending_arch_ascending", "brachiocephalic", "left_common_carotid",
                         "left_subclavian"]


def test_a_mixed_pool_names_the_aortic_wire_for_its_arches_only(tmp_path):
    out, _, index = specs(tmp_path, 6, 12)
    kinds = {e["set"] for e in index}
    assert kinds == {"coronary", "arch"}  # 12 draws of two kinds: both present for this seed
    for e in index:
        if e["set"] == "arch":
            wire = out.parent / e["wire"]
            shipped = guidewire_nav.REPO_ROOT / "engine" / "wire" / "aortic_035_angled.json"
            assert wire.read_bytes() == shipped.read_bytes()
        else:
            assert "wire" not in e  # the run's wire (the coronary wire by default)


def test_varied_wires_are_drawn_per_anatomy_within_their_ranges_and_leave_the_specs_alone(tmp_path):
    out, varied_specs, index = specs(tmp_path, 6, 12, options=["--vary-wires"], name="varied")
    _, plain_specs, _ = specs(tmp_path, 6, 12)
    assert varied_specs == plain_specs  # same anatomies
    wires = [json.loads((out.parent / e["wire"]).read_text()) for e in index]
    assert len({w["friction"] for w in wires}) == len(wires)  # one draw each
    for e, w in zip(index, wires):
        base = json.loads((guidewire_nav.REPO_ROOT / "engine" / "wire" / anatomy_pool.BASE_WIRES[e["set"]]).read_text())
        r = anatomy_pool.WIRE_RANGES[e["set"]]
        assert r["tip_length_mm"][0] <= w["tip_length_mm"] <= r["tip_length_mm"][1]
        bend_deg = np.degrees(w["tip_curvature_per_mm"] * w["tip_length_mm"])
        assert r["tip_bend_deg"][0] - 0.1 <= bend_deg <= r["tip_bend_deg"][1] + 0.1
        assert r["friction"][0] <= w["friction"] <= r["friction"][1]
        assert w["tip_length_mm"] < w["fine_region_mm"]  # the bent length on the fine tip elements
        assert {k: v for k, v in w.items() if k not in ("tip_length_mm", "tip_curvature_per_mm", "friction", "comment")} \
            == {k: v for k, v in base.items() if k not in ("tip_length_mm", "tip_curvature_per_mm", "friction", "comment")}
    again, _, _ = specs(tmp_path / "again", 6, 12, options=["--vary-wires"], name="varied")
    assert [(again / "wires" / f"{e['name']}.json").read_text() for e in index] == \
        [(out / "wires" / f"{e['name']}.json").read_text() for e in index]  # same seed, same wires
    if guidewire_nav.app_path("guidewire-server").is_file():  # the engine takes a drawn wire
        from guidewire_nav.env import GuidewireEnv
        env = GuidewireEnv(anatomies="t1_straight_y", server_args=["--wire", str(out.parent / index[0]["wire"])])
        try:
            assert env.spec_reply["anatomies"][0]["wire_diameter_mm"] == wires[0]["diameter_mm"]
            env.reset(seed=0)
        finally:
            env.close()


def test_a_beating_pool_gives_every_coronary_tree_a_rest_shaped_field_and_a_rate(tmp_path):
    _, beating, index = specs(tmp_path, 6, 12, options=["--beating"], name="beating")
    _, plain, _ = specs(tmp_path, 6, 12)
    rates = []
    for e, spec, p in zip(index, beating, plain):
        if e["set"] != "coronary":
            assert "heart_rate_bpm" not in e and spec == p  # arches do not beat
            continue
        assert spec["deformation"]["phase"] == 0  # the mesh is the rest shape, as resolve_heart_motion needs
        assert spec["branches"] == p["branches"]  # the same tree
        assert 0 <= e["heart_rate_bpm"] <= anatomy_pool.MAX_HEART_RATE_BPM
        assert f"{e['heart_rate_bpm']} bpm" in spec["description"]
        rates.append(e["heart_rate_bpm"])
    assert len(set(rates)) == len(rates) > 2


def test_one_server_beats_an_anatomy_at_the_rate_its_index_entry_names(tmp_path):
    if not guidewire_nav.app_path("guidewire-server").is_file():
        pytest.skip("guidewire-server not built; set GW_BUILD_DIR")
    stem = guidewire_nav.REPO_ROOT / "anatomies" / "test" / "coronary" / "coronary"  # its field is at phase 0
    rows = [{"name": "beats", "mesh": f"{stem}.stl", "truth": f"{stem}.truth.json", "heart_rate_bpm": 90},
            {"name": "still", "mesh": f"{stem}.stl", "truth": f"{stem}.truth.json"}]
    (tmp_path / "b").mkdir()
    index = tmp_path / "b" / "index.json"
    index.write_text(json.dumps({"anatomies": rows}))
    from guidewire_nav.env import GuidewireEnv
    env = GuidewireEnv(anatomies=str(index))
    try:
        served = {a["name"]: a.get("heart_rate_bpm") for a in env.spec_reply["anatomies"]}
        assert served == {"beats": 90.0, "still": None}
    finally:
        env.close()
    index.write_text(json.dumps({"anatomies": [dict(rows[0], heart_rate_bpm=-5)]}))
    bad = subprocess.run([str(guidewire_nav.app_path("guidewire-server")), "--port", "0", "--anatomies", str(index)],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode != 0 and "heart_rate_bpm" in bad.stderr and "beats" in bad.stderr


def test_a_bad_kind_is_refused_by_name(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        anatomy_pool.main(["--out", str(tmp_path), "--count", "1", "--seed", "0", "--kinds", "coronary,vein"])
    assert e.value.code == 2
    assert "--kinds" in capsys.readouterr().err


def test_a_meshed_pool_is_served_by_its_index(tmp_path):
    gen, server = guidewire_nav.app_path("anatomy-gen"), guidewire_nav.app_path("guidewire-server")
    if not gen.is_file() or not server.is_file():
        pytest.skip("anatomy-gen or guidewire-server not built; set GW_BUILD_DIR")
    out = tmp_path / "pool"
    assert anatomy_pool.main(["--out", str(out), "--count", "2", "--seed", "11", "--jobs", "2",
                              "--anatomy-gen", str(gen)]) == 0
    index = json.loads((out / "index.json").read_text())["anatomies"]
    assert len(index) == 2 and all((out.parent / e["mesh"]).is_file() for e in index)
    # a second run keeps the meshes it finds
    mtimes = [(out.parent / e["mesh"]).stat().st_mtime_ns for e in index]
    assert anatomy_pool.main(["--out", str(out), "--count", "2", "--seed", "11", "--anatomy-gen", str(gen)]) == 0
    assert mtimes == [(out.parent / e["mesh"]).stat().st_mtime_ns for e in index]
    from guidewire_nav.env import GuidewireEnv
    env = GuidewireEnv(anatomies=str(out / "index.json"))
    try:
        names = env.anatomy_names
        assert names == [e["name"] for e in index]
        obs, info = env.reset(seed=1)
        assert np.all(np.isfinite(obs)) and info["anatomy"] in names
    finally:
        env.close()
    bad = subprocess.run([str(server), "--port", "0", "--anatomies", str(tmp_path / "missing.json")],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode != 0 and "missing.json" in bad.stderr


def test_one_server_serves_each_anatomy_with_the_wire_its_index_names(tmp_path):
    if not guidewire_nav.app_path("guidewire-server").is_file():
        pytest.skip("guidewire-server not built; set GW_BUILD_DIR")
    root = guidewire_nav.REPO_ROOT
    rows = []
    for name, wire in [("t1_straight_y", "aortic_035_angled.json"), ("t2_curved_straight_exit", None)]:
        stem = root / "anatomies" / "train" / name / name
        rows.append({"name": name, "mesh": f"{stem}.stl", "truth": f"{stem}.truth.json"})
        if wire:
            rows[-1]["wire"] = str(root / "engine" / "wire" / wire)
    (tmp_path / "mixed").mkdir()
    index = tmp_path / "mixed" / "index.json"
    index.write_text(json.dumps({"anatomies": rows}))
    from guidewire_nav.env import GuidewireEnv
    env = GuidewireEnv(anatomies=str(index))
    try:
        wires = {a["name"]: a["wire_diameter_mm"] for a in env.spec_reply["anatomies"]}
        assert wires == {"t1_straight_y": 0.889, "t2_curved_straight_exit": pytest.approx(0.3556, abs=1e-4)}
        for seed in range(4):  # episodes on both anatomies step without a physics problem
            env.reset(seed=seed)
            _, _, _, _, info = env.step(np.array([0.0], dtype=np.float32))
            assert "problem" not in info
    finally:
        env.close()


def test_evaluate_takes_a_pool_as_a_row(tmp_path):
    evaluate = guidewire_nav.app_path("evaluate")
    if not evaluate.is_file():
        pytest.skip("evaluate not built; set GW_BUILD_DIR")
    out, _, index = specs(tmp_path, 4, 3, kinds="coronary")
    plan = subprocess.run([str(evaluate), "--plan", "--rows", f"var1,{out / 'index.json'}"], capture_output=True,
                          text=True, check=True)
    rows = json.loads(plan.stdout)["rows"]
    assert [r["name"] for r in rows] == ["sensitivity: var1", f"pool {out / 'index.json'}"]
    assert rows[1]["episodes"] == 5 * len(index)


def test_a_spec_the_generator_refuses_is_drawn_again_and_kept_on_a_rerun(tmp_path):
    # A stand-in for anatomy-gen that refuses every first draw, as the real one refuses intersecting branches.
    gen = tmp_path / "fake-anatomy-gen"
    gen.write_text("""#!/usr/bin/env python3
import json, pathlib, sys
spec, out = pathlib.Path(sys.argv[sys.argv.index("--spec") + 1]), pathlib.Path(sys.argv[sys.argv.index("--out") + 1])
s = json.loads(spec.read_text())
if "Redraw" not in s["description"]:
    sys.exit(f"error: {spec}: branches 'B2' and 'F5' intersect")
(out / (s["name"] + ".stl")).write_text("solid x\\nendsolid x\\n")
(out / (s["name"] + ".truth.json")).write_text("{}")
print(json.dumps({"name": s["name"]}))
""")
    gen.chmod(0o755)
    out = tmp_path / "pool"
    args = ["--out", str(out), "--count", "2", "--seed", "5", "--anatomy-gen", str(gen)]
    assert anatomy_pool.main(args) == 0
    index = json.loads((out / "index.json").read_text())["anatomies"]
    assert [e["name"] for e in index] == ["coronary_5_0000", "coronary_5_0001"]
    redrawn = [json.loads((out.parent / e["spec"]).read_text()) for e in index]
    assert all("Redraw 1" in s["description"] for s in redrawn)
    first = anatomy_pool.sample_spec(5, 0, ["coronary"])[1]
    assert redrawn[0]["branches"] != first["branches"]  # drawn from (5, 0, 1), not (5, 0)
    assert redrawn[0] == anatomy_pool.sample_spec(5, 0, ["coronary"], 1)[1]
    # A rerun keeps the meshed anatomies with their redrawn specs (the first draw is not written over them).
    assert anatomy_pool.main(args) == 0
    assert [json.loads((out.parent / e["spec"]).read_text()) for e in index] == redrawn


def test_a_pool_rerun_with_other_options_is_refused_naming_the_anatomy(tmp_path, capsys):
    # A stand-in for anatomy-gen that meshes every spec (writes placeholder files).
    gen = tmp_path / "fake-anatomy-gen"
    gen.write_text("""#!/usr/bin/env python3
import json, pathlib, sys
spec, out = pathlib.Path(sys.argv[sys.argv.index("--spec") + 1]), pathlib.Path(sys.argv[sys.argv.index("--out") + 1])
s = json.loads(spec.read_text())
(out / (s["name"] + ".stl")).write_text("solid x\\nendsolid x\\n")
(out / (s["name"] + ".truth.json")).write_text("{}")
print(json.dumps({"name": s["name"]}))
""")
    gen.chmod(0o755)
    args = ["--out", str(tmp_path / "pool"), "--count", "2", "--seed", "5", "--anatomy-gen", str(gen)]
    assert anatomy_pool.main(args + ["--beating"]) == 0
    assert anatomy_pool.main(args + ["--beating", "--vary-wires"]) == 0  # wires are the index's: no conflict
    with pytest.raises(SystemExit) as e:
        anatomy_pool.main(args)  # the meshed trees were drawn beating
    assert "coronary_5_0000.spec.json" in str(e.value) and "other options" in str(e.value)
