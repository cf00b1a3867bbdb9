"""The stub arches (issue 64 item 4): validation arches whose great vessels are cut to stubs 1, 2 and 3 of their own
radii long, as a phantom or a cropped scan shows them. Their specs are what make_arch_specs.py --stubs writes, each
stub ends the radii it claims outside the aortic lumen, and `centerline` finds their four targets from the command
line (centerline/README.md "Great vessels cut to stubs"; all nine in tests/centerline/test_stub_arches.cpp)."""
import importlib.util
import json
import subprocess
from pathlib import Path

import pytest

import guidewire_nav

REPO = Path(__file__).resolve().parents[2]
ARCHES = REPO / "anatomies" / "validation" / "arches"


def arch_specs():
    spec = importlib.util.spec_from_file_location("make_arch_specs", REPO / "anatomies/segmentation/make_arch_specs.py")
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


@pytest.mark.parametrize("k", [1, 2, 3])
def test_stub_specs_are_the_scripts_and_end_k_radii_outside(k):
    m = arch_specs()
    for name, height, tb, tc, ts, _, _ in m.VALIDATION_ARCHES:
        desc = m.STUB_DESCRIPTION.format(base=name, k=k)
        spec, outside = m.stub_arch(f"{name}_stub{k}", height, tb, tc, ts, k, desc)
        assert (ARCHES / f"{name}_stub{k}.spec.json").read_text() == m.spec_text(spec)
        for b in spec["branches"][1:]:
            r = b["radius"][0]
            assert k * r <= outside[b["name"]] <= k * r + 0.5, (name, b["name"])  # walked out in 0.25 mm steps
        full = json.loads((ARCHES / f"{name}.spec.json").read_text())
        assert spec["branches"][0] == full["branches"][0]  # the same aorta as the full validation arch


@pytest.mark.parametrize("k", [1, 2, 3])
def test_centerline_finds_the_stubs(tmp_path, k):
    gen, centerline = guidewire_nav.app_path("anatomy-gen"), guidewire_nav.app_path("centerline")
    if not gen.is_file() or not centerline.is_file():
        pytest.skip("anatomy-gen or centerline not built; set GW_BUILD_DIR")
    name = f"arch_val_type2_stub{k}"
    subprocess.run([str(gen), "--spec", str(ARCHES / f"{name}.spec.json"), "--out", str(tmp_path)], check=True,
                   capture_output=True)
    truth = json.loads((tmp_path / f"{name}.truth.json").read_text())
    inlet = ",".join(str(v) for v in truth["inlet"]["position"])
    r = subprocess.run([str(centerline), "--anatomy", str(tmp_path / f"{name}.stl"), "--inlet", inlet, "--no-cache",
                        "--out", str(tmp_path / "c.json"), "--verbose"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    got = json.loads((tmp_path / "c.json").read_text())
    assert (len(got["targets"]), len(got["bifurcations"])) == (4, 3)
    for t in truth["targets"]:  # each true end has its own extracted target within half its radius
        nearest = min(sum((a - b) ** 2 for a, b in zip(t["position"], e["position"])) ** 0.5 for e in got["targets"])
        assert nearest <= 0.5 * t["radius"], t["id"]
    assert "vessel end(s) the first skeleton missed" in r.stderr
