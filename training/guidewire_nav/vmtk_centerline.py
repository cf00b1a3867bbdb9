"""VMTK centerlines of every anatomy in anatomies/index.json (or `--index FILE`, e.g. the
segmentation-like set's manifest.json), for bench-centerline.

VMTK is the reference tool the C++ extractor is compared with (issue 4). It needs
Python >= 3.12 and lives in its own virtual environment, apart from the training venv:

    ~/.pyenv/versions/3.12.1/bin/python -m venv /path/vmtk-venv
    /path/vmtk-venv/bin/pip install vmtk
    /path/vmtk-venv/bin/python training/guidewire_nav/vmtk_centerline.py > vmtk.json
    build/apps/bench-centerline --vmtk vmtk.json
    /path/vmtk-venv/bin/python training/guidewire_nav/vmtk_centerline.py --index SET/manifest.json > vmtk_set.json
    build/apps/bench-centerline --index SET/manifest.json --vmtk vmtk_set.json

VMTK gets the file exactly as a user has it (no repair): a mesh whose manifest entry says
"scale_hint": "m" gets its seeds in metres and its centerline scaled back to mm.

For each anatomy, vmtkcenterlines (Voronoi diagram + fast marching, seeds given as
points: the true inlet as source, the true targets as targets, so VMTK gets the same
help our extractor gets from --inlet) runs on the STL, resampled every 0.5 mm. Prints
one JSON object {name: {"seconds": s, "lines": [{"points": [[x,y,z]...], "radii": [...]}]}}
where radii are VMTK's maximum inscribed sphere radii. This file imports vmtk, so it is
not imported by the package (run it as a script).
"""
import contextlib
import json
import sys
import time
from pathlib import Path


def centerlines(stl: Path, source, targets):
    from vmtk import vmtkscripts  # imported here: only the vmtk venv has it

    reader = vmtkscripts.vmtkSurfaceReader()
    reader.InputFileName = str(stl)
    reader.Execute()
    start = time.perf_counter()
    cl = vmtkscripts.vmtkCenterlines()
    cl.Surface = reader.Surface
    cl.SeedSelectorName = "pointlist"
    cl.SourcePoints = list(source)
    cl.TargetPoints = [c for t in targets for c in t]
    cl.Resampling = 1
    cl.ResamplingStepLength = 0.5
    cl.AppendEndPoints = 1
    cl.Execute()
    seconds = time.perf_counter() - start
    poly = cl.Centerlines
    radius = poly.GetPointData().GetArray("MaximumInscribedSphereRadius")
    lines = []
    for c in range(poly.GetNumberOfCells()):
        ids = poly.GetCell(c).GetPointIds()
        pts = [list(poly.GetPoint(ids.GetId(i))) for i in range(ids.GetNumberOfIds())]
        rad = [radius.GetValue(ids.GetId(i)) for i in range(ids.GetNumberOfIds())]
        lines.append({"points": pts, "radii": rad})
    return seconds, lines


def main(argv):
    args = argv[1:]
    index_path = Path(__file__).resolve().parents[2] / "anatomies" / "index.json"
    if args[:1] == ["--index"]:
        index_path, args = Path(args[1]).resolve(), args[2:]
    root = index_path.parent.parent  # paths in an index are relative to its folder's parent
    index = json.loads(index_path.read_text())
    only = set(args)
    out = {}
    for a in index["anatomies"]:
        if only and a["name"] not in only:
            continue
        mesh, truth_path = root / a["mesh"], root / a["truth"]
        if not mesh.exists() or not truth_path.exists():
            continue
        truth = json.loads(truth_path.read_text())
        unit = 0.001 if a.get("scale_hint") == "m" else 1.0
        source = [c * unit for c in truth["inlet"]["position"]]
        targets = [[c * unit for c in t["position"]] for t in truth["targets"]]
        try:
            with contextlib.redirect_stdout(sys.stderr):  # vmtk logs on stdout
                seconds, lines = centerlines(mesh, source, targets)
            for line in lines:
                line["points"] = [[c / unit for c in p] for p in line["points"]]
                line["radii"] = [r / unit for r in line["radii"]]
            out[a["name"]] = {"seconds": seconds, "lines": lines}
        except Exception as e:  # report, keep going with the other anatomies
            out[a["name"]] = {"error": str(e)}
        print(a["name"], out[a["name"]].get("seconds", "error"), file=sys.stderr)
    json.dump(out, sys.stdout)
    print()


if __name__ == "__main__":
    main(sys.argv)
