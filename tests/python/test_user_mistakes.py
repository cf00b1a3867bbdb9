"""Each app's and script's most likely mistakes get one clear error naming the flag or file, a non-zero exit
and no traceback (issue 65 item 3): a missing file, a wrong extension, contradictory flags, NaN or out-of-range
values, a file of the wrong kind."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import app_or_skip as app

REPO = Path(__file__).resolve().parents[2]
T1 = str(REPO / "anatomies/train/t1_straight_y/t1_straight_y.stl")




def run(args, stdin=""):
    return subprocess.run(args, capture_output=True, text=True, input=stdin, cwd=REPO, timeout=300)


def error_line(r):
    """The one error line: the last line of stderr (CLI11's "Run with --help" hint after it aside), which must
    name the problem; no traceback anywhere."""
    assert r.returncode != 0, f"exit 0 for a mistake: {r.stdout[-500:]} {r.stderr[-500:]}"
    assert "Traceback" not in r.stderr, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.strip() and ln != "Run with --help for more information."]
    assert lines, f"no message on stderr (stdout: {r.stdout[-300:]})"
    return lines[-1]


@pytest.mark.parametrize("args, names", [
    (["--anatomy", "/nonexistent/vessels.stl", "--list"], ["/nonexistent/vessels.stl"]),
    (["--anatomy", str(REPO / "README.md"), "--list"], ["README.md"]),
    (["--anatomy", T1, "--inlet", "nan,0,0", "--list"], ["--inlet", "finite"]),
    (["--anatomy", T1, "--target-point", "1,2", "--list"], ["--target-point"]),
    (["--anatomy", T1, "--target", "9"], ["target", "9"]),
    (["--anatomy", T1, "--target", "1", "--recovery-assist"], ["--recovery-assist", "--recovery"]),
    (["--anatomy", T1, "--target", "1", "--push-speed", "nan"], ["--push-speed"]),
    (["--anatomy", T1, "--target", "1", "--task", "/nonexistent/task.json"], ["--task", "/nonexistent/task.json"]),
    (["--anatomy", T1, "--replay", str(REPO / "training/tasks/paper.json")], ["paper.json", "not a plan"]),
    (["--anatomy", T1, "--replay", "/nonexistent/plan.json"], ["/nonexistent/plan.json"]),
])
def test_navigate(args, names):
    line = error_line(run([app("navigate"), *args]))
    for n in names:
        assert n in line, line


@pytest.mark.parametrize("args, names", [
    (["--anatomy", T1], ["--target"]),
    (["--anatomy", T1, "--target", "9"], ["target", "9"]),
    (["--anatomy", T1, "--target", "1", "--force-limit", "0"], ["--force-limit"]),
    (["--anatomy", T1, "--target", "1", "--inlet", "1,nan,2"], ["--inlet"]),
    (["--anatomy", "/nonexistent/x.stl", "--target", "1"], ["/nonexistent/x.stl"]),
])
def test_plan(args, names):
    line = error_line(run([app("plan"), *args]))
    for n in names:
        assert n in line, line


def test_the_other_apps(tmp_path):
    missing = "/nonexistent/vessels.stl"
    assert missing in error_line(run([app("mesh-info"), "--anatomy", missing]))
    assert "--inlet" in error_line(run([app("centerline"), "--anatomy", T1, "--inlet", "nan,0,0"]))
    assert "--rows" in error_line(run([app("evaluate"), "--rows", "no-such-row", "--plan"]))
    assert "--from-json" in error_line(run([app("evaluate"), "--from-json", "/nonexistent/results.json"]))
    for planned in ("some", "-1", "2x"):  # a number of seeds or 'episodes'
        line = error_line(run([app("evaluate"), "--rows", "coronary-like", "--planned-seeds", planned, "--plan"]))
        assert "--planned-seeds" in line and planned in line, line
    # a missing or broken actor is refused before any row runs (was: every row "skipped", exit 0)
    (tmp_path / "actor.json").write_text("[1, 2, 3]")
    for actor in ("/nonexistent/actor.json", str(tmp_path / "actor.json")):
        line = error_line(run([app("evaluate"), "--policy", actor, "--rows", "coronary-like", "--episode-scale", "0.01",
                               "--out", str(tmp_path / "eval")]))
        assert "--policy" in line and actor in line, line
        assert not (tmp_path / "eval" / "results.json").exists()
    # bench-mechanics takes STEM or STEM.stl; a mesh without a generated truth says what it needs
    line = error_line(run([app("bench-mechanics"), "--anatomy", str(REPO / "README.md")]))
    assert "truth.json" in line and "STEM" in line
    assert "actor.json" in error_line(run([app("policy-run"), "--policy", str(tmp_path / "actor.json")], "0\n"))


def test_python_entry_points(tmp_path):
    r = run([sys.executable, "scripts/plot_torque_transmission.py", "--help"])
    assert r.returncode == 0 and "usage" in r.stdout
    assert "/nonexistent/runs.json" in error_line(
        run([sys.executable, "scripts/plot_torque_transmission.py", "/nonexistent/runs.json", str(tmp_path / "x.png")]))
    assert "--index" in error_line(run([sys.executable, "-m", "guidewire_nav.plot_anatomies", "--index", "/nonexistent.json"]))
    r = run([sys.executable, "-m", "guidewire_nav.plot_anatomies", "--help"])
    assert "runs/anatomies.png" in r.stdout  # the tracked picture is not the default output


def test_mesh_info_reports_repairs_as_every_app_does(tmp_path):
    """Repairs go to stderr as `repaired: FILE: ...` (README), whatever else mesh-info prints."""
    import numpy as np  # a box with one face missing: the intake caps it
    v = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0], [0, 0, 10], [10, 0, 10], [10, 10, 10], [0, 10, 10]], float)
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6)]
    path = tmp_path / "open_box.stl"
    with open(path, "w") as f:
        f.write("solid s\n")
        for a, b, c in faces:
            f.write("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in v[[a, b, c]])
                    + "endloop\nendfacet\n")
        f.write("endsolid s\n")
    r = run([app("mesh-info"), "--anatomy", str(path)])
    assert r.returncode == 0, r.stderr
    repaired = [ln for ln in r.stderr.splitlines() if ln.startswith("repaired:")]
    assert repaired and all(ln.startswith(f"repaired: {path}: ") for ln in repaired), r.stderr
    assert "repaired:" not in r.stdout
