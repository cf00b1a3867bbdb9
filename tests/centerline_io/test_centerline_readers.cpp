// Bring your own centerline (issue 35 item 4): VMTK .vtp and 3D Slicer .mrk.json read through
// read_centerline into the truth's tree, target points picked by nearest_target, bad files
// refused with the file and the problem named. Fixtures: tests/data (tests/data/make_fixtures.py).
// Truth: anatomies/train/t1_straight_y (trunk (0,0,0)->(0,0,60), target 1 (-27,0,126), target 2
// (27,0,126), radius 1.75 mm).
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "base/graph/centerline_graph.hpp"
#include "base/graph/declared_coordinate_space.hpp"
#include "base/graph/nearest_target.hpp"
#include "base/graph/read_slicer_markups.hpp"
#include "base/graph/read_vmtk_centerline.hpp"

using namespace gw;

namespace {

std::string data(const std::string& relative) { return std::string(GW_SOURCE_DIR) + "/tests/data/" + relative; }

const CenterlineGraph& truth() {
  static const CenterlineGraph g =
      read_centerline(std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y.truth.json");
  return g;
}

double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const Eigen::Vector3d ab = line[i + 1] - line[i];
    const double t = std::clamp((p - line[i]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (line[i] + t * ab)).norm());
  }
  return best;
}

// Largest distance of any point of `g` to the truth's polylines.
double max_distance_to_truth(const CenterlineGraph& g) {
  double worst = 0.0;
  for (const auto& b : g.branches)
    for (const auto& p : b.points) {
      double d = std::numeric_limits<double>::infinity();
      for (const auto& tb : truth().branches) d = std::min(d, distance_to_polyline(p, tb.points));
      worst = std::max(worst, d);
    }
  return worst;
}

// Same tree as the truth: a trunk, one bifurcation into two leaves, targets numbered alike.
void check_y_topology(const CenterlineGraph& g, double position_tolerance) {
  REQUIRE(g.branches.size() == 3);
  REQUIRE(g.bifurcations.size() == 1);
  REQUIRE(g.targets.size() == 2);
  for (size_t i = 0; i < g.branches.size(); ++i) CHECK(g.branches[i].id == static_cast<int>(i));
  CHECK(g.branches[0].parent == -1);
  CHECK(g.branches[1].parent == 0);
  CHECK(g.branches[2].parent == 0);
  CHECK(g.bifurcations[0].parent == 0);
  CHECK(g.bifurcations[0].children == std::vector<int>{1, 2});
  CHECK(g.inlet.branch == 0);
  CHECK((g.inlet.position - truth().inlet.position).norm() <= position_tolerance);
  CHECK((g.inlet_direction - Eigen::Vector3d::UnitZ()).norm() < 1e-3);
  for (int k = 0; k < 2; ++k) {
    CHECK(g.targets[k].id == k + 1);
    CHECK((g.targets[k].position - truth().targets[k].position).norm() <= position_tolerance);
    CHECK(g.branches[g.targets[k].branch].points.back() == g.targets[k].position);
  }
  // A child starts at its parent's bifurcation centre.
  for (int c : g.bifurcations[0].children) CHECK(g.branches[c].points.front() == g.bifurcations[0].position);
  CHECK(g.branches[0].points.back() == g.bifurcations[0].position);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = std::string(GW_BINARY_DIR) + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace

TEST_CASE("VMTK centerlines in every vtkXMLPolyDataWriter encoding give the truth's tree", "[centerline_io][vmtk]") {
  // Written by VTK 9.7.2 from the truth's own points (one line per target sharing the trunk), so
  // the tree must come back exactly: points within 1e-4 mm (float32 storage: ~1e-5 mm at 126 mm).
  for (const char* name : {"y_ascii.vtp", "y_binary_zlib.vtp", "y_binary_raw64.vtp", "y_appended_raw_zlib.vtp",
                           "y_appended_raw.vtp", "y_appended_base64.vtp", "y_reversed.vtp", "y_slicer_lps.vtp"}) {
    INFO(name);
    const CenterlineGraph g = read_centerline(data(std::string("vmtk/") + name));
    check_y_topology(g, 1e-4);
    CHECK((g.bifurcations[0].position - truth().bifurcations[0].position).norm() < 1e-4);
    for (size_t b = 0; b < 3; ++b) {
      REQUIRE(g.branches[b].points.size() == truth().branches[b].points.size());
      for (size_t i = 0; i < g.branches[b].points.size(); ++i) {
        CHECK((g.branches[b].points[i] - truth().branches[b].points[i]).norm() < 1e-4);
        CHECK(g.branches[b].radii[i] == Approx(1.75).margin(1e-9));
      }
    }
    CHECK(g.inlet.radius == Approx(1.75));
    CHECK(g.targets[0].radius == Approx(1.75));
  }
}

TEST_CASE("vmtkcenterlines' own output on t1_straight_y gives the truth's tree", "[centerline_io][vmtk]") {
  // vmtk 1.5.2 (VTK 9.6.2): inline base64, zlib, header UInt32, Float32 points, Int64 cells.
  const CenterlineGraph g = read_centerline(data("vmtk/t1_straight_y_vmtkcenterlines.vtp"));
  check_y_topology(g, 0.05);
  // Its axes: within 5% of the radius (0.0875 mm) of the true axes everywhere (measured 0.069 mm).
  UNSCOPED_INFO("VMTK max distance to the true axes " << max_distance_to_truth(g) << " mm");
  CHECK(max_distance_to_truth(g) < 0.05 * 1.75);
  // Its radii: the maximum inscribed sphere, 1.75 mm on the tubes, larger in the junction's crotch.
  CHECK(g.inlet.radius == Approx(1.75).epsilon(0.01));
  for (const auto& t : g.targets) CHECK(t.radius == Approx(1.75).epsilon(0.03));
  // The bifurcation is where the paths begin to part (VMTK's lines are identical up to there):
  // measured 0.82 mm (0.47 radius) proximal of the true centre, on the axis.
  const double off = (g.bifurcations[0].position - truth().bifurcations[0].position).norm();
  UNSCOPED_INFO("VMTK bifurcation at " << g.bifurcations[0].position.transpose() << ", " << off << " mm from the truth");
  CHECK(off < 0.6 * 1.75);
}

TEST_CASE("Slicer curves in LPS and RAS give the truth's tree in RAS", "[centerline_io][slicer]") {
  // Control points every 5 mm of the truth (the curved branches' chords are within 0.03 mm of
  // the arcs); the LPS file holds (-x, -y, z), the "right" curve is drawn target to bifurcation.
  for (const char* name : {"slicer/y_curves_lps.mrk.json", "slicer/y_curves_ras.mrk.json"}) {
    INFO(name);
    const CenterlineGraph g = read_centerline(data(name));
    check_y_topology(g, 1e-3);
    CHECK((g.bifurcations[0].position - truth().bifurcations[0].position).norm() < 1e-3);
    CHECK(max_distance_to_truth(g) < 0.03);
    CHECK(g.targets[1].position.x() > 26.9);  // LPS -> RAS: x negated back
  }
  // Radii: the RAS file has a "Radius" measurement, the LPS one none (0 = unknown).
  const CenterlineGraph ras = read_centerline(data("slicer/y_curves_ras.mrk.json"));
  for (const auto& b : ras.branches)
    for (double r : b.radii) CHECK(r == Approx(1.75));
  const CenterlineGraph lps = read_slicer_markups(data("slicer/y_curves_lps.mrk.json"));
  for (const auto& b : lps.branches)
    for (double r : b.radii) CHECK(r == 0.0);
}

TEST_CASE("Slicer fiducials pick their targets through nearest_target", "[centerline_io][slicer]") {
  for (const char* name : {"slicer/y_curves_lps.mrk.json", "slicer/y_curves_ras.mrk.json"}) {
    INFO(name);
    const CenterlineGraph g = read_centerline(data(name));
    const std::vector<SlicerPoint> points = read_slicer_points(data(name));
    REQUIRE(points.size() == 2);
    CHECK(points[0].label == "target 1");
    CHECK(points[0].position.isApprox(Eigen::Vector3d(-28, 0, 126.5)));  // RAS, LPS file included
    CHECK(nearest_target(g, points[0].position) == 1);
    CHECK(nearest_target(g, points[1].position) == 2);
  }
}

TEST_CASE("nearest_target refuses points far from every target end", "[centerline_io][target_point]") {
  const CenterlineGraph& g = truth();
  CHECK(nearest_target(g, Eigen::Vector3d(26, 1, 125)) == 2);
  // 3 radii = 5.25 mm: 5 mm off is taken, 6 mm is not.
  CHECK(nearest_target(g, Eigen::Vector3d(-27, 5, 126)) == 1);
  CHECK_THROWS_WITH(nearest_target(g, Eigen::Vector3d(-27, 6, 126)),
                    Catch::Contains("6.00 mm from the nearest target end (target 1), more than 5.25 mm") &&
                        Catch::Contains("targets: 1 (-27.00, 0.00, 126.00), 2 (27.00, 0.00, 126.00)"));
  CHECK_THROWS_WITH(nearest_target(g, Eigen::Vector3d(0, 0, 30)), Catch::Contains("nearer the inlet"));
  CenterlineGraph none = g;
  none.targets.clear();
  CHECK_THROWS_WITH(nearest_target(none, Eigen::Vector3d::Zero()), Catch::Contains("no target"));
  // Radius unknown (0, a Slicer curve without radii): at least kTargetPointMinMm.
  const CenterlineGraph lps = read_centerline(data("slicer/y_curves_lps.mrk.json"));
  CHECK(nearest_target(lps, Eigen::Vector3d(27, 1.9, 126)) == 2);
  CHECK_THROWS_WITH(nearest_target(lps, Eigen::Vector3d(27, 2.1, 126)), Catch::Contains("more than 2.00 mm"));
}

TEST_CASE("broken VMTK files are refused naming the file and the problem", "[centerline_io][vmtk][errors]") {
  const auto message = [](const std::string& name) {
    try {
      read_centerline(data("vmtk/" + name));
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const auto starts_with_path = [](const std::string& name) { return Catch::StartsWith(data("vmtk/" + name) + ": "); };
  CHECK_THAT(message("bad_base64.vtp"),
             starts_with_path("bad_base64.vtp") && Catch::Contains("point array 'MaximumInscribedSphereRadius'") &&
                 Catch::Contains("bad base64: character '@' is not base64"));
  CHECK_THAT(message("bad_array_name.vtp"),
             starts_with_path("bad_array_name.vtp") &&
                 Catch::Contains("point array 'MaximumInscribedSphereRadius' is missing (point arrays here: Radius)"));
  CHECK_THAT(message("bad_truncated.vtp"), starts_with_path("bad_truncated.vtp") && Catch::Contains("truncated"));
  CHECK_THAT(message("bad_zlib.vtp"),
             starts_with_path("bad_zlib.vtp") && Catch::Contains("zlib data of block 1 of 1 cannot be inflated"));
  CHECK_THAT(message("bad_type.vtp"), starts_with_path("bad_type.vtp") && Catch::Contains("type 'String', not a number type"));
  CHECK_THAT(message("bad_no_lines.vtp"), starts_with_path("bad_no_lines.vtp") && Catch::Contains("no lines"));
  CHECK_THAT(message("missing.vtp"), Catch::Contains("missing.vtp: cannot open file"));

  const std::string ascii = [] {
    std::ifstream in(data("vmtk/y_ascii.vtp"));
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  CHECK_THROWS_WITH(read_centerline(write_temp("not_xml.vtp", "hello")), Catch::Contains("not a readable VTK XML file"));
  CHECK_THROWS_WITH(read_centerline(write_temp("cut.vtp", ascii.substr(0, ascii.size() / 2))),
                    Catch::Contains("not a readable VTK XML file"));
  std::string grid = ascii;
  grid.replace(grid.find("type=\"PolyData\""), 15, "type=\"ImageData\"");
  CHECK_THROWS_WITH(read_centerline(write_temp("grid.vtp", grid)), Catch::Contains("'ImageData' file, not PolyData"));
  std::string lz4 = ascii;
  lz4.replace(lz4.find("header_type"), 11, "compressor=\"vtkLZ4DataCompressor\" header_type");
  CHECK_THROWS_WITH(read_centerline(write_temp("lz4.vtp", lz4)), Catch::Contains("vtkLZ4DataCompressor' is not supported"));
  std::string bad_id = ascii;
  const size_t conn = bad_id.find("Name=\"connectivity\"", bad_id.find("<Lines>"));
  const size_t first = bad_id.find_first_of("0123456789", bad_id.find('>', conn) + 1);
  bad_id.replace(first, 1, "9999");
  CHECK_THROWS_WITH(read_centerline(write_temp("bad_id.vtp", bad_id)), Catch::Contains("is not one of the 530 points"));
}

TEST_CASE("broken Slicer markups are refused naming the file and the problem", "[centerline_io][slicer][errors]") {
  const std::string head = R"({"@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#", "markups": [)";
  const auto curve = [](const std::string& name, const std::string& points) {
    return R"({"type": "Curve", "name": ")" + name + R"(", "coordinateSystem": "RAS", "controlPoints": [)" + points + "]}";
  };
  const auto cp = [](double x, double y, double z) {
    return R"({"position": [)" + std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z) + "]}";
  };
  const std::string trunk = curve("trunk", cp(0, 0, 0) + "," + cp(0, 0, 30) + "," + cp(0, 0, 60));
  CHECK_THROWS_WITH(centerline_from_json(head + R"({"type": "Fiducial", "controlPoints": []}]})", "f.mrk.json"),
                    Catch::StartsWith("f.mrk.json: no Curve, ClosedCurve or Line markup"));
  CHECK_THROWS_WITH(centerline_from_json(head + trunk + "," + curve("stray", cp(20, 0, 30) + "," + cp(40, 0, 30)) + "]}",
                                         "s.mrk.json"),
                    Catch::StartsWith("s.mrk.json: markup 1 'stray' does not start on another curve"));
  CHECK_THROWS_WITH(centerline_from_json(head + trunk + "," + curve("side", cp(0, 0, 0) + "," + cp(10, 0, 5)) + "]}",
                                         "i.mrk.json"),
                    Catch::Contains("leaves the tree at the inlet"));
  CHECK_THROWS_WITH(centerline_from_json(head + curve("one", cp(0, 0, 0)) + "]}", "o.mrk.json"),
                    Catch::Contains("fewer than 2 distinct control points"));
  CHECK_THROWS_WITH(
      centerline_from_json(head + R"({"type": "Curve", "coordinateSystem": "XYZ", "controlPoints": []}]})", "x.mrk.json"),
      Catch::Contains("coordinateSystem 'XYZ'"));
  CHECK_THROWS_WITH(centerline_from_json(head + R"({"type": "Curve", "controlPoints": [{"position": [1, 2]}]}]})", "p.mrk.json"),
                    Catch::Contains("position is not 3 numbers"));
  CHECK_THROWS_WITH(read_centerline(write_temp("broken.mrk.json", head + "{")), Catch::Contains("broken.mrk.json: malformed"));
  // A side branch starting 1 mm off the trunk's axis leaves from the trunk point nearest it.
  const CenterlineGraph g = centerline_from_json(
      head + trunk + "," + curve("side", cp(1, 0, 20) + "," + cp(10, 0, 25) + "," + cp(20, 0, 30)) + "]}", "ok.mrk.json");
  REQUIRE(g.bifurcations.size() == 1);
  CHECK(g.bifurcations[0].position.isApprox(Eigen::Vector3d(0, 0, 20)));
  CHECK(g.targets.size() == 2);
}

TEST_CASE("declared_coordinate_space reads Slicer's SPACE tag from a mesh header", "[centerline_io][slicer]") {
  std::string stl(80, '\0');
  stl.replace(0, 27, "3D Slicer output. SPACE=LPS");
  CHECK(declared_coordinate_space(write_temp("lps.stl", stl + std::string(4, '\0'))) == "LPS");
  CHECK(declared_coordinate_space(write_temp("ras.obj", "# 3D Slicer output. SPACE=RAS\nv 0 0 0\n")) == "RAS");
  CHECK(declared_coordinate_space(write_temp("plain.obj", "v 0 0 0\n")).empty());
  CHECK(declared_coordinate_space(data("nothing-here.stl")).empty());
}
