// VTK XML PolyData files: well-formed XML, counts in the Piece header matching the data
// arrays, indices in range, the documented arrays present.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "apps/report/atomic_write.hpp"
#include "apps/report/vtp_writer.hpp"
#include "report_scenes.hpp"

using namespace gw;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

struct DataArray {
  std::string section;  // PointData, CellData, Points, Lines, Polys
  std::map<std::string, std::string> attr;
  std::vector<double> values;
};

struct Vtp {
  std::map<std::string, std::string> piece;
  std::vector<DataArray> arrays;
  long number(const char* key) const { return std::stol(piece.at(key)); }
  const DataArray& array(const std::string& section, const std::string& name) const {
    for (const auto& a : arrays)
      if (a.section == section && a.attr.count("Name") && a.attr.at("Name") == name) return a;
    throw std::runtime_error("no array " + section + "/" + name);
  }
};

std::map<std::string, std::string> attributes(const std::string& tag) {
  std::map<std::string, std::string> out;
  std::size_t at = 0;
  while ((at = tag.find('=', at)) != std::string::npos) {
    std::size_t k = tag.rfind(' ', at);
    const std::string key = tag.substr(k + 1, at - k - 1);
    const std::size_t q0 = tag.find('"', at), q1 = tag.find('"', q0 + 1);
    out[key] = tag.substr(q0 + 1, q1 - q0 - 1);
    at = q1 + 1;
  }
  return out;
}

// A small XML reader for our files: checks every element is closed in order and collects
// DataArrays with the section they belong to.
Vtp parse_vtp(const std::string& path) {
  std::ifstream in(path);
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (xml.rfind("<?xml", 0) != 0) throw std::runtime_error("no XML declaration");
  Vtp vtp;
  std::vector<std::string> stack;
  std::size_t at = xml.find("?>") + 2;
  DataArray* open_array = nullptr;
  while ((at = xml.find('<', at)) != std::string::npos) {
    const std::size_t end = xml.find('>', at);
    if (end == std::string::npos) throw std::runtime_error("unterminated tag");
    const std::string tag = xml.substr(at + 1, end - at - 1);
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (stack.empty() || stack.back() != name) throw std::runtime_error("mismatched </" + name + ">");
      stack.pop_back();
      open_array = nullptr;
    } else {
      const std::string name = tag.substr(0, tag.find(' '));
      const bool self_closing = tag.back() == '/';
      if (name == "Piece") vtp.piece = attributes(tag);
      if (name == "DataArray") {
        vtp.arrays.push_back({stack.back(), attributes(tag), {}});
        open_array = &vtp.arrays.back();
        std::istringstream text(xml.substr(end + 1, xml.find('<', end) - end - 1));
        double v;
        while (text >> v) open_array->values.push_back(v);
        if (!text.eof()) throw std::runtime_error("unparsable number in DataArray");
      }
      if (!self_closing) stack.push_back(name);
    }
    at = end + 1;
  }
  if (!stack.empty()) throw std::runtime_error("unclosed <" + stack.back() + ">");
  return vtp;
}

// Counts in the header agree with the arrays; connectivity indices are in range.
void check_consistent(const Vtp& v) {
  const long np = v.number("NumberOfPoints");
  const long nl = v.number("NumberOfLines"), npoly = v.number("NumberOfPolys");
  long cells = 0;
  for (const auto& a : v.arrays) {
    const long comps = a.attr.count("NumberOfComponents") ? std::stol(a.attr.at("NumberOfComponents")) : 1;
    CAPTURE(a.section, a.attr.count("Name") ? a.attr.at("Name") : "");
    if (a.section == "Points") CHECK(static_cast<long>(a.values.size()) == 3 * np);
    if (a.section == "PointData") CHECK(static_cast<long>(a.values.size()) == comps * np);
    if (a.section == "CellData") CHECK(static_cast<long>(a.values.size()) == comps * (nl + npoly));
  }
  for (const char* section : {"Lines", "Polys"}) {
    const long n = std::string(section) == "Lines" ? nl : npoly;
    if (n == 0) continue;
    const auto& conn = v.array(section, "connectivity").values;
    const auto& off = v.array(section, "offsets").values;
    REQUIRE(static_cast<long>(off.size()) == n);
    CHECK(off.back() == static_cast<double>(conn.size()));
    for (std::size_t i = 1; i < off.size(); ++i) CHECK(off[i] >= off[i - 1]);
    for (double i : conn) CHECK((i >= 0 && i < np));
    cells += n;
  }
  CHECK(cells == nl + npoly);
}

}  // namespace

TEST_CASE("mesh VTP: vertices as points, triangles as polys", "[report][vtp]") {
  const std::string path = test::scratch_dir("vtp_mesh") + "/vessel.vtp";
  write_mesh_vtp(test::box_vessel(), path);
  const Vtp v = parse_vtp(path);
  CHECK(v.number("NumberOfPoints") == 8);
  CHECK(v.number("NumberOfPolys") == 12);
  CHECK(v.number("NumberOfLines") == 0);
  check_consistent(v);
  CHECK(v.array("Polys", "connectivity").values.size() == 36);
  CHECK(v.array("Polys", "offsets").values[0] == 3);
  const auto& pts = v.array("Points", "Points").values;
  CHECK(pts[3 * 7 + 1] == 40.0);  // vertex 7 = (2, 40, 2)
}

TEST_CASE("trace VTP: tip polyline with point data and the final wire as a second line", "[report][vtp]") {
  EpisodeTrace t = test::box_trace();
  t.tip[3] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());  // a diverged frame
  t.action[4] = std::numeric_limits<double>::infinity();
  const std::string path = test::scratch_dir("vtp_trace") + "/episode.vtp";
  write_trace_vtp(t, path);
  const Vtp v = parse_vtp(path);
  const long frames = static_cast<long>(t.time_s.size()) - 1;  // NaN frame skipped
  const long wire = static_cast<long>(t.wire_shapes.back().size());
  CHECK(v.number("NumberOfPoints") == frames + wire);
  CHECK(v.number("NumberOfLines") == 2);
  check_consistent(v);
  CHECK(v.array("Lines", "offsets").values == std::vector<double>{static_cast<double>(frames), static_cast<double>(frames + wire)});
  CHECK(v.array("CellData", "kind").values == std::vector<double>{0, 1});
  const auto& time = v.array("PointData", "time_s").values;
  const auto& frame = v.array("PointData", "frame").values;
  const auto& control = v.array("PointData", "agent_in_control").values;
  CHECK(frame[3] == 4);  // frame 3 was skipped
  CHECK(time[3] == Approx(0.4));
  CHECK(v.array("PointData", "action").values[3] == 0.0);  // infinite action written as 0
  CHECK(control[0] == 0);
  CHECK(control[frames - 1] == 1);
  CHECK(frame[static_cast<std::size_t>(frames)] == 38);  // wire points carry the shape's frame
}

TEST_CASE("wire-shape VTP: one polyline per recorded shape with its frame and time", "[report][vtp]") {
  const test::TreeScene s = test::small_tree();
  const EpisodeTrace t = test::episode_along(plan_path(s.graph, 1).points, s.graph, "success", "", 1);
  const std::string dir = test::scratch_dir("vtp_shapes");
  write_wire_shapes_vtp(t, dir + "/shapes.vtp");
  const Vtp v = parse_vtp(dir + "/shapes.vtp");
  CHECK(v.number("NumberOfLines") == static_cast<long>(t.wire_shapes.size()));
  check_consistent(v);
  const auto& frame = v.array("CellData", "frame").values;
  for (std::size_t i = 0; i < frame.size(); ++i) CHECK(frame[i] == t.wire_shape_frame[i]);
  EpisodeTrace none = t;
  none.wire_shapes.clear();
  none.wire_shape_frame.clear();
  CHECK_THROWS_WITH(write_wire_shapes_vtp(none, dir + "/none.vtp"), Contains("no wire shape"));
}

TEST_CASE("polyline and centerline VTP carry arc length and radius", "[report][vtp]") {
  const test::TreeScene s = test::small_tree();
  const TargetPath path = plan_path(s.graph, 2);
  const std::string dir = test::scratch_dir("vtp_path");
  write_polyline_vtp(path.points, dir + "/path.vtp", path.radii);
  const Vtp v = parse_vtp(dir + "/path.vtp");
  CHECK(v.number("NumberOfPoints") == static_cast<long>(path.points.size()));
  CHECK(v.number("NumberOfLines") == 1);
  check_consistent(v);
  CHECK(v.array("PointData", "arc_length_mm").values.back() == Approx(path.length).epsilon(1e-8));
  CHECK(v.array("PointData", "radius_mm").values.front() == Approx(path.radii.front()));

  write_centerline_vtp(s.graph, dir + "/centerline.vtp");
  const Vtp c = parse_vtp(dir + "/centerline.vtp");
  CHECK(c.number("NumberOfLines") == static_cast<long>(s.graph.branches.size()));
  check_consistent(c);
  CHECK(c.array("CellData", "parent").values == std::vector<double>{-1, 0, 0, 2, 2});

  CHECK_THROWS_WITH(write_polyline_vtp(path.points, dir + "/r.vtp", {1.0, 2.0}), Contains(dir + "/r.vtp") && Contains("2 radii"));
  CHECK_THROWS_WITH(write_polyline_vtp({}, dir + "/e.vtp"), Contains("no points"));
}

TEST_CASE("VTP writers refuse bad input and unwritable paths without leaving files", "[report][vtp]") {
  const std::string dir = test::scratch_dir("vtp_bad");
  CHECK_THROWS_WITH(write_mesh_vtp(TriangleMesh{}, dir + "/empty.vtp"), Contains("empty"));
  TriangleMesh nan_mesh = test::box_vessel();
  nan_mesh.V(2, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(write_mesh_vtp(nan_mesh, dir + "/nan.vtp"), Contains("vertex 2"));
  TriangleMesh bad_index = test::box_vessel();
  bad_index.F(0, 0) = 8;
  CHECK_THROWS_WITH(write_mesh_vtp(bad_index, dir + "/index.vtp"), Contains("index 8"));
  const std::string unwritable = dir + "/missing/vessel.vtp";
  CHECK_THROWS_AS(write_mesh_vtp(test::box_vessel(), unwritable), ReportError);
  CHECK_THROWS_WITH(write_mesh_vtp(test::box_vessel(), unwritable), Contains(unwritable));
  CHECK_THROWS_AS(write_trace_vtp(test::box_trace(), unwritable), ReportError);
  CHECK_THROWS_WITH(write_trace_vtp(test::box_trace(), unwritable), Contains(unwritable));
  CHECK(fs::is_empty(dir));
}

TEST_CASE("trace VTP of an episode that diverged at once (no finite tip, no wire) is still valid", "[report][vtp]") {
  EpisodeTrace t;
  t.outcome = "diverged";
  t.detail = "NaN at the first step";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  t.time_s = {0.0, 0.01};
  t.tip = {Eigen::Vector3d::Constant(nan), Eigen::Vector3d::Constant(nan)};
  t.action = {nan, nan};
  t.agent_in_control = {false, true};
  const std::string path = test::scratch_dir("vtp_empty") + "/episode.vtp";
  write_trace_vtp(t, path);
  const Vtp v = parse_vtp(path);
  CHECK(v.number("NumberOfPoints") == 0);
  CHECK(v.number("NumberOfLines") == 1);
  check_consistent(v);
}
