"""The layers of docs/architecture.md ("Include direction"), enforced: every `#include "folder/..."`
of the C++ libraries must reach a folder its own folder may use, and CGAL stays inside the centerline
extraction and the generator's .cpp files (slow to compile; no header may pull it in).

A new dependency that breaks a layer fails here; widening ALLOWED is a design change that belongs in
docs/architecture.md first."""
import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LIBRARIES = ("engine", "centerline", "policy", "apps")

# Each library folder and the folders (besides itself) it may include, lowest layer first.
BASE = {"engine/mesh", "centerline/graph", "engine/solver", "engine/wire", "policy"}
MECHANICS = {"engine/mesh", "engine/solver", "engine/wire", "engine/scene", "engine/contact", "engine/sim"}
ALLOWED = {
    "engine/mesh": set(), "centerline/graph": set(), "engine/solver": set(), "engine/wire": set(), "policy": set(),
    "engine/scene": {"engine/mesh"},
    "engine/contact": {"engine/mesh", "engine/solver", "engine/wire", "engine/scene"},
    "engine/sim": {"engine/mesh", "engine/solver", "engine/wire", "engine/scene", "engine/contact"},
    "engine/task": MECHANICS | {"centerline/graph"},                 # gets a CenterlineGraph, not the extraction
    "centerline/extract": {"centerline/graph", "engine/mesh"},       # not the generator
    "centerline/vessel_tree": {"centerline/graph", "engine/mesh"},   # not the extraction
    "apps/report": BASE | MECHANICS | {"engine/task"},
    "apps/server": BASE | MECHANICS | {"engine/task", "apps/report"},  # not the runner
    "apps/runner": BASE | MECHANICS | {"engine/task", "centerline/extract", "centerline/vessel_tree", "apps/report"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
CGAL = re.compile(r"^\s*#\s*include\s+<CGAL/", re.M)


def library_folder(path):
    """'engine/sim' for engine/sim/step.cpp; 'apps' for an executable apps/navigate.cpp."""
    parts = path.relative_to(REPO).parts
    return "/".join(parts[:2]) if len(parts) > 2 else parts[0]


def sources():
    for top in LIBRARIES:
        for p in sorted((REPO / top).rglob("*")):
            if p.suffix in (".hpp", ".cpp", ".h") and p.is_file():
                yield p


def test_every_library_folder_has_a_layer():
    folders = {library_folder(p) for p in sources()} - {"apps"}
    assert folders <= set(ALLOWED), f"folders without a layer in ALLOWED: {sorted(folders - set(ALLOWED))}"


def test_includes_go_down_the_layers():
    bad = []
    for p in sources():
        own = library_folder(p)
        if own == "apps":  # the executables may use every library
            continue
        for target in INCLUDE.findall(p.read_text(errors="replace")):
            parts = target.split("/")
            if len(parts) < 3 or parts[0] not in LIBRARIES:
                continue  # a header of the same folder by bare name, or not ours
            folder = "/".join(parts[:2])
            if folder != own and folder not in ALLOWED[own]:
                bad.append(f"{p.relative_to(REPO)} includes {target} ({own} may not use {folder})")
    assert not bad, "includes against the layers (docs/architecture.md):\n" + "\n".join(bad)


def test_cgal_stays_in_the_extraction_and_generator_sources():
    bad = [str(p.relative_to(REPO)) for p in sources() if CGAL.search(p.read_text(errors="replace"))
           and not (p.suffix == ".cpp" and library_folder(p) in ("centerline/extract", "centerline/vessel_tree"))]
    assert not bad, "CGAL included outside centerline/extract and centerline/vessel_tree .cpp files: " + ", ".join(bad)


def test_the_check_sees_a_violation(tmp_path, monkeypatch):
    """The scan itself works: a header of the mechanics that includes the task is reported."""
    fake = tmp_path / "engine" / "sim" / "bad.hpp"
    fake.parent.mkdir(parents=True)
    fake.write_text('#pragma once\n#include "engine/task/episode.hpp"\n')
    monkeypatch.setattr(__import__(__name__), "REPO", tmp_path)
    try:
        test_includes_go_down_the_layers()
    except AssertionError as e:
        assert "engine/sim may not use engine/task" in str(e)
    else:
        raise AssertionError("a forbidden include was not reported")
