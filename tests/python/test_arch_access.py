"""navigate on an aortic arch's bare surface (no truth beside it, no --inlet): entered at the descending aorta, the
femoral access (issue 64 item 4), said on stderr with the --inlet that would enter at the other aortic end."""

import json
import subprocess

from conftest import REPO, app_or_skip


def test_a_bare_arch_surface_is_entered_at_the_descending_aorta(tmp_path):
    gen, navigate = app_or_skip("anatomy-gen"), app_or_skip("navigate")
    spec = REPO / "anatomies/segmentation/arch_type2.spec.json"
    subprocess.run([gen, "--spec", str(spec), "--out", str(tmp_path)], check=True, capture_output=True)
    (tmp_path / "arch_type2.truth.json").unlink()  # a user's surface: nothing says where the wire enters
    truth = json.loads((REPO / "anatomies/segmentation/arch_type2.truth.json").read_text())
    r = subprocess.run([navigate, "--anatomy", str(tmp_path / "arch_type2.stl"), "--list", "--no-cache"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    x, y, z = truth["inlet"]["position"]
    assert f"inlet at ({x:.2f}, {y:.2f}, {z:.2f}) mm" in r.stdout  # the truth's inlet: the descending aorta
    note = [line for line in r.stderr.splitlines() if "aortic arch: entered at the descending aorta" in line]
    assert len(note) == 1 and note[0].startswith("note: ") and "--inlet" in note[0] and "guess" not in note[0]
    # The ascending aorta, the wider end, is a target now.
    assert "14.3" in r.stdout.splitlines()[-1]
