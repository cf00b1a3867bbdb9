"""Writes the centerline-reader fixtures in tests/data/vmtk and tests/data/slicer.

Not run in CI: the files it writes are committed. It needs the `vtk` package (9.x, from PyPI),
which is not a project dependency; use a throwaway virtual environment:

    python3 -m venv .cache/vtkvenv && .cache/vtkvenv/bin/pip install vtk
    .cache/vtkvenv/bin/python tests/data/make_fixtures.py [--vmtk-output T1_VMTK.vtp]

Truth: anatomies/train/t1_straight_y/t1_straight_y.truth.json (a Y: trunk (0,0,0)->(0,0,60),
branches to (-27,0,126) = target 1 and (27,0,126) = target 2, radius 1.75 mm everywhere).

VMTK fixtures (what vmtkcenterlines writes: one polyline per inlet-to-target path, each with its
own copy of the shared trunk points, point array MaximumInscribedSphereRadius) are written with
vtkXMLPolyDataWriter, the writer vmtkcenterlines uses, once per encoding:
  y_ascii.vtp                 ascii
  y_binary_zlib.vtp           inline base64, zlib, header UInt32, Float32 points (as vmtk 1.5.2)
  y_binary_raw64.vtp          inline base64, uncompressed, header UInt64, Int32 connectivity
  y_appended_raw_zlib.vtp     appended raw, zlib, header UInt64
  y_appended_raw.vtp          appended raw, uncompressed
  y_appended_base64.vtp       appended base64, uncompressed, Int32 connectivity
  y_reversed.vtp              lines stored target -> inlet (ascii)
  y_slicer_lps.vtp            as 3D Slicer saves a model: LPS coordinates, field data SPACE=LPS
  bad_*.vtp                   broken on purpose (see the test)
t1_straight_y_vmtkcenterlines.vtp is vmtkcenterlines' own output (vmtk 1.5.2, VTK 9.6.2) on
anatomies/train/t1_straight_y/t1_straight_y.stl with source (0,0,0) and targets
(-27,0,126), (27,0,126), resampled every 0.5 mm (see training/guidewire_nav/vmtk_centerline.py);
it is copied in (from --vmtk-output, when given), not made here.

Slicer fixtures follow markups-schema-v1.0.3: a trunk curve, two branch curves starting at the
bifurcation (the second drawn backwards, target to bifurcation), and a point list with one
fiducial 1 mm off each target end:
  y_curves_lps.mrk.json   coordinateSystem LPS (Slicer's default), no radii
  y_curves_ras.mrk.json   coordinateSystem RAS, with a "Radius" measurement per control point
"""
import argparse
import json
import shutil
from pathlib import Path

import vtk

ROOT = Path(__file__).resolve().parents[2]
TRUTH = ROOT / "anatomies/train/t1_straight_y/t1_straight_y.truth.json"
VMTK = ROOT / "tests/data/vmtk"
SLICER = ROOT / "tests/data/slicer"


def vmtk_lines(truth):
    """One inlet-to-target path per target: trunk points, then the leaf's (its first is the trunk's last)."""
    b = truth["branches"]
    lines = []
    for leaf in (1, 2):
        pts = b[0]["points"] + b[leaf]["points"][1:]
        rad = b[0]["radii"] + b[leaf]["radii"][1:]
        lines.append((pts, rad))
    return lines


def polydata(lines, lps=False, int32=False, reverse=False):
    points = vtk.vtkPoints()
    points.SetDataTypeToDouble()
    radius = vtk.vtkDoubleArray()
    radius.SetName("MaximumInscribedSphereRadius")
    cells = vtk.vtkCellArray()
    for pts, rad in lines:
        if reverse:
            pts, rad = pts[::-1], rad[::-1]
        ids = []
        for p, r in zip(pts, rad):
            x, y, z = p
            ids.append(points.InsertNextPoint(-x if lps else x, -y if lps else y, z))
            radius.InsertNextValue(r)
        cells.InsertNextCell(len(ids), ids)
    if int32:
        cells.ConvertTo32BitStorage()
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    poly.SetLines(cells)
    poly.GetPointData().AddArray(radius)
    if lps:
        space = vtk.vtkStringArray()
        space.SetName("SPACE")
        space.InsertNextValue("LPS")
        poly.GetFieldData().AddArray(space)
    return poly


def write(poly, name, mode, zlib=False, header64=False, encode_appended=False):
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(str(VMTK / name))
    w.SetInputData(poly)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary, "appended": w.SetDataModeToAppended}[mode]()
    if zlib:
        w.SetCompressorTypeToZLib()
    else:
        w.SetCompressorTypeToNone()
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.SetEncodeAppendedData(1 if encode_appended else 0)
    assert w.Write() == 1, name


def float32_copy(poly):
    out = vtk.vtkPolyData()
    out.DeepCopy(poly)
    pts = vtk.vtkPoints()
    pts.SetDataTypeToFloat()
    for i in range(poly.GetNumberOfPoints()):
        pts.InsertNextPoint(poly.GetPoint(i))
    out.SetPoints(pts)
    return out


def write_vmtk(truth, vmtk_output=None):
    VMTK.mkdir(parents=True, exist_ok=True)
    lines = vmtk_lines(truth)
    plain = polydata(lines)
    write(plain, "y_ascii.vtp", "ascii")
    write(float32_copy(plain), "y_binary_zlib.vtp", "binary", zlib=True)
    write(polydata(lines, int32=True), "y_binary_raw64.vtp", "binary", header64=True)
    write(plain, "y_appended_raw_zlib.vtp", "appended", zlib=True, header64=True)
    write(plain, "y_appended_raw.vtp", "appended")
    write(polydata(lines, int32=True), "y_appended_base64.vtp", "appended", encode_appended=True)
    write(polydata(lines, reverse=True), "y_reversed.vtp", "ascii")
    write(polydata(lines, lps=True), "y_slicer_lps.vtp", "binary", zlib=True)

    # Broken on purpose.
    text = (VMTK / "y_binary_raw64.vtp").read_text()
    start = text.index('Name="MaximumInscribedSphereRadius"')
    start = text.index(">", start) + 1
    while text[start] in " \n":
        start += 1
    (VMTK / "bad_base64.vtp").write_text(text[: start + 40] + "@#!" + text[start + 43:])
    (VMTK / "bad_array_name.vtp").write_text(
        (VMTK / "y_ascii.vtp").read_text().replace('Name="MaximumInscribedSphereRadius"', 'Name="Radius"'))
    raw = (VMTK / "y_appended_raw_zlib.vtp").read_bytes()
    (VMTK / "bad_truncated.vtp").write_bytes(raw[: len(raw) * 2 // 3])
    (VMTK / "bad_type.vtp").write_text((VMTK / "y_ascii.vtp").read_text().replace(
        'type="Float64" Name="MaximumInscribedSphereRadius"', 'type="String" Name="MaximumInscribedSphereRadius"'))
    # A zlib block cut short inside otherwise valid base64: re-encode the radius array with its last
    # compressed bytes dropped and the header left claiming the full size.
    import base64
    import struct
    import zlib as z
    text = (VMTK / "y_binary_zlib.vtp").read_text()
    start = text.index('Name="MaximumInscribedSphereRadius"')
    start = text.index(">", start) + 1
    end = text.index("<", start)
    body = text[start:end].strip()
    header = base64.b64decode(body[:24])  # 4 UInt32: blocks=1, block size, last size, compressed size
    blocks, size, last, csize = struct.unpack("<4I", header)
    data = base64.b64decode(body[24:])
    assert blocks == 1 and len(data) == csize and z.decompress(data)
    cut = data[: csize // 2]
    bad = base64.b64encode(struct.pack("<4I", 1, size, last, len(cut))).decode() + base64.b64encode(cut).decode()
    (VMTK / "bad_zlib.vtp").write_text(text[:start] + "\n          " + bad + "\n        " + text[end:])
    (VMTK / "bad_no_lines.vtp").write_text(
        (VMTK / "y_ascii.vtp").read_text().replace('NumberOfLines="2"', 'NumberOfLines="0"'))

    if vmtk_output is not None:
        shutil.copy(vmtk_output, VMTK / "t1_straight_y_vmtkcenterlines.vtp")


def control_point(i, label, p):
    return {"id": str(i + 1), "label": label, "description": "", "associatedNodeID": "",
            "position": [round(c, 4) for c in p], "orientation": [-1.0, -0.0, -0.0, -0.0, -1.0, -0.0, 0.0, 0.0, 1.0],
            "selected": True, "locked": False, "visibility": True, "positionStatus": "defined"}


def curve(name, pts, rad, lps, with_radius):
    pts = [[-p[0], -p[1], p[2]] if lps else p for p in pts]
    m = {"type": "Curve", "coordinateSystem": "LPS" if lps else "RAS", "coordinateUnits": "mm", "locked": False,
         "fixedNumberOfControlPoints": False, "labelFormat": name + "-%d", "lastUsedControlPointNumber": len(pts),
         "controlPoints": [control_point(i, f"{name}-{i + 1}", p) for i, p in enumerate(pts)],
         "measurements": [{"name": "length", "enabled": False, "units": "mm", "printFormat": "%-#4.4g%s"}],
         "display": {"visibility": True, "opacity": 1.0, "color": [0.39, 0.39, 0.39]}}
    if with_radius:
        m["measurements"].append({"name": "Radius", "enabled": False, "units": "mm", "printFormat": "%5.3f %s",
                                  "controlPointValues": rad})
    return m


def every(points, step):
    """Every step-th point and the last: control points as a user (or a resampling) would place them."""
    idx = list(range(0, len(points), step))
    if idx[-1] != len(points) - 1:
        idx.append(len(points) - 1)
    return idx


def write_slicer(truth):
    SLICER.mkdir(parents=True, exist_ok=True)
    b = truth["branches"]
    for lps in (True, False):
        markups = []
        for k, name in ((0, "trunk"), (1, "left"), (2, "right")):
            idx = every(b[k]["points"], 10)  # 5 mm apart
            pts = [b[k]["points"][i] for i in idx]
            rad = [b[k]["radii"][i] for i in idx]
            if k == 2:  # drawn from the target back to the bifurcation
                pts, rad = pts[::-1], rad[::-1]
            markups.append(curve(name, pts, rad, lps, with_radius=not lps))
        fids = []
        for t in truth["targets"]:
            x, y, z = t["position"]
            p = [x + (1.0 if x > 0 else -1.0), y, z + 0.5]  # a click just beyond the end, as on a surface
            fids.append(control_point(len(fids), f"target {t['id']}", [-p[0], -p[1], p[2]] if lps else p))
        markups.append({"type": "Fiducial", "coordinateSystem": "LPS" if lps else "RAS", "coordinateUnits": "mm",
                        "locked": False, "labelFormat": "F-%d", "controlPoints": fids,
                        "measurements": [], "display": {"visibility": True}})
        doc = {"@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/"
                          "Resources/Schema/markups-schema-v1.0.3.json#", "markups": markups}
        (SLICER / f"y_curves_{'lps' if lps else 'ras'}.mrk.json").write_text(json.dumps(doc, indent=2) + "\n")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--vmtk-output", type=Path,
                   help="vmtkcenterlines' output on t1_straight_y, copied to t1_straight_y_vmtkcenterlines.vtp "
                        "(without it the committed copy stays)")
    a = p.parse_args(argv)
    if a.vmtk_output is not None and not a.vmtk_output.is_file():
        p.error(f"--vmtk-output {a.vmtk_output}: no such file")
    truth = json.loads(TRUTH.read_text())
    write_vmtk(truth, a.vmtk_output)
    write_slicer(truth)
    print("vtk", vtk.vtkVersion.GetVTKVersion(), "->", VMTK, SLICER)


if __name__ == "__main__":
    main()
