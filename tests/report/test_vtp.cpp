// VTK XML PolyData files (zlib-compressed appended binary): well-formed XML, counts in the Piece
// header matching the data arrays, indices in range, the documented arrays present; the project's
// own .vtp reader (base/graph/vtp_polylines) reads them back; .pvd time series.
#include <zlib.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <pugixml.hpp>
#include <sstream>

#include "lib/report/atomic_write.hpp"
#include "lib/report/vtp_writer.hpp"
#include "base/graph/vtp_polylines.hpp"
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

std::uint64_t le64(const std::string& d, std::size_t at) {
  if (at + 8 > d.size()) throw std::runtime_error("appended data ends inside a header");
  std::uint64_t v = 0;
  for (int k = 7; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(d[at + static_cast<std::size_t>(k)]);
  return v;
}

// One appended array: vtkZLibDataCompressor's UInt64 header [blocks, block size, last block size,
// compressed sizes], then the zlib blocks; inflated with zlib and checked against the header.
std::string inflate_array(const std::string& appended, std::size_t offset) {
  const std::uint64_t blocks = le64(appended, offset), block = le64(appended, offset + 8),
                      last = le64(appended, offset + 16);
  std::size_t at = offset + 24 + 8 * blocks;
  std::string out;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t packed = le64(appended, offset + 24 + 8 * b);
    const std::uint64_t expected = (b + 1 == blocks && last != 0) ? last : block;
    if (at + packed > appended.size()) throw std::runtime_error("appended data truncated");
    std::string raw(expected, '\0');
    uLongf n = static_cast<uLongf>(expected);
    if (uncompress(reinterpret_cast<Bytef*>(raw.data()), &n, reinterpret_cast<const Bytef*>(appended.data() + at),
                   static_cast<uLong>(packed)) != Z_OK || n != expected)
      throw std::runtime_error("zlib block does not inflate to its size");
    out += raw;
    at += packed;
  }
  return out;
}

std::vector<double> decode_values(const std::string& bytes, const std::string& type) {
  std::vector<double> out;
  if (type == "Float64") {
    for (std::size_t i = 0; i + 8 <= bytes.size(); i += 8) {
      double v;
      std::memcpy(&v, bytes.data() + i, 8);
      out.push_back(v);
    }
  } else if (type == "Int32") {
    for (std::size_t i = 0; i + 4 <= bytes.size(); i += 4) {
      std::int32_t v;
      std::memcpy(&v, bytes.data() + i, 4);
      out.push_back(v);
    }
  } else {
    throw std::runtime_error("unexpected type " + type);
  }
  return out;
}

// A small reader for our files (XML by pugixml, appended raw data inflated by zlib): checks the
// header attributes the format needs and collects the DataArrays with the section they belong to.
Vtp parse_vtp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (file.rfind("<?xml", 0) != 0) throw std::runtime_error("no XML declaration");
  const std::size_t tag = file.find("<AppendedData encoding=\"raw\">");
  if (tag == std::string::npos) throw std::runtime_error("no raw <AppendedData>");
  const std::size_t underscore = file.find('_', tag);
  const std::size_t close = file.rfind("</AppendedData>");
  if (underscore == std::string::npos || close == std::string::npos || close < underscore)
    throw std::runtime_error("malformed <AppendedData>");
  const std::string appended = file.substr(underscore + 1, close - underscore - 1);
  const std::string header = file.substr(0, tag) + "</VTKFile>";
  pugi::xml_document xml;
  if (!xml.load_string(header.c_str())) throw std::runtime_error("XML header does not parse");
  const pugi::xml_node root = xml.child("VTKFile");
  if (std::string(root.attribute("type").value()) != "PolyData" ||
      std::string(root.attribute("byte_order").value()) != "LittleEndian" ||
      std::string(root.attribute("header_type").value()) != "UInt64" ||
      std::string(root.attribute("compressor").value()) != "vtkZLibDataCompressor")
    throw std::runtime_error("unexpected VTKFile attributes");
  Vtp vtp;
  const pugi::xml_node piece = root.child("PolyData").child("Piece");
  for (const pugi::xml_attribute a : piece.attributes()) vtp.piece[a.name()] = a.value();
  for (const pugi::xml_node section : piece.children())
    for (const pugi::xml_node a : section.children("DataArray")) {
      DataArray d{section.name(), {}, {}};
      for (const pugi::xml_attribute at : a.attributes()) d.attr[at.name()] = at.value();
      if (d.attr["format"] != "appended") throw std::runtime_error("an array is not appended");
      d.values = decode_values(inflate_array(appended, std::stoul(d.attr.at("offset"))), d.attr.at("type"));
      vtp.arrays.push_back(std::move(d));
    }
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

TEST_CASE("episode series: a .pvd listing one wire file per recorded shape, with the wall", "[report][vtp]") {
  const test::TreeScene s = test::small_tree();
  const EpisodeTrace t = test::episode_along(plan_path(s.graph, 1).points, s.graph, "success", "", 1);
  REQUIRE(t.wire_shapes.size() >= 2);
  const std::string dir = test::scratch_dir("vtp_series");
  fs::create_directories(dir + "/ep");
  // A moving wall: the mesh shifted by t mm in x at time t, written by the caller's callback.
  SeriesWall wall;
  int walls_written = 0;
  wall.file_at = [&](double time) {
    TriangleMesh m = s.mesh;
    m.V.col(0).array() += time;
    const std::string name = "ep/vessel_" + std::to_string(walls_written++) + ".vtp";
    write_mesh_vtp(m, dir + "/" + name);
    return name;
  };
  const auto written = write_episode_series(t, dir + "/ep.pvd", "ep", wall);
  REQUIRE(written.size() == t.wire_shapes.size() + 1);
  CHECK(walls_written == static_cast<int>(t.wire_shapes.size()));
  CHECK(written.back() == dir + "/ep.pvd");
  std::ifstream in(dir + "/ep.pvd");
  const std::string pvd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  pugi::xml_document xml;
  REQUIRE(xml.load_string(pvd.c_str()));
  const pugi::xml_node root = xml.child("VTKFile");
  CHECK(std::string(root.attribute("type").value()) == "Collection");
  std::vector<pugi::xml_node> sets;
  for (const pugi::xml_node d : root.child("Collection").children("DataSet")) sets.push_back(d);
  REQUIRE(sets.size() == 2 * t.wire_shapes.size());
  for (std::size_t k = 0; k < t.wire_shapes.size(); ++k) {
    const int f = t.wire_shape_frame[k];
    const double time = t.time_s[static_cast<std::size_t>(f)];
    const pugi::xml_node w = sets[2 * k], m = sets[2 * k + 1];
    CAPTURE(k, f);
    CHECK(w.attribute("timestep").as_double() == time);
    CHECK(m.attribute("timestep").as_double() == time);
    CHECK(w.attribute("part").as_int() == 0);
    CHECK(m.attribute("part").as_int() == 1);
    const Vtp wv = parse_vtp(dir + "/" + w.attribute("file").value());
    check_consistent(wv);
    CHECK(wv.number("NumberOfLines") == 2);
    CHECK(wv.array("CellData", "kind").values == std::vector<double>{0, 1});
    CHECK(wv.array("CellData", "frame").values == std::vector<double>{static_cast<double>(f), static_cast<double>(f)});
    // Tip trace up to the frame, then the wire shape.
    CHECK(wv.number("NumberOfPoints") == static_cast<long>(f + 1 + static_cast<int>(t.wire_shapes[k].size())));
    const auto& pts = wv.array("Points", "Points").values;
    CHECK(pts[3 * static_cast<std::size_t>(f + 1)] == t.wire_shapes[k][0].x());
    const Vtp mv = parse_vtp(dir + "/" + m.attribute("file").value());
    CHECK(mv.number("NumberOfPolys") == s.mesh.F.rows());
    CHECK(mv.array("Points", "Points").values[0] == Approx(s.mesh.V(0, 0) + time));
  }
  // A static wall is listed, not written, at every time.
  SeriesWall fixed;
  fixed.static_file = "vessel.vtp";
  const auto still = write_episode_series(t, dir + "/still.pvd", "ep", fixed);
  CHECK(still.size() == t.wire_shapes.size() + 1);
  std::ifstream in2(dir + "/still.pvd");
  const std::string pvd2((std::istreambuf_iterator<char>(in2)), std::istreambuf_iterator<char>());
  CHECK(pvd2.find("part=\"1\" file=\"vessel.vtp\"") != std::string::npos);

  EpisodeTrace none = t;
  none.wire_shapes.clear();
  none.wire_shape_frame.clear();
  CHECK_THROWS_WITH(write_episode_series(none, dir + "/none.pvd", "ep"), Contains("no wire shape"));
  CHECK_THROWS_WITH(write_wire_shape_vtp(t, t.wire_shapes.size(), dir + "/x.vtp"), Contains("wire shape"));
}

TEST_CASE("the project's own .vtp reader reads the binary files back", "[report][vtp]") {
  const test::TreeScene s = test::small_tree();
  const std::string path = test::scratch_dir("vtp_roundtrip") + "/centerline.vtp";
  write_centerline_vtp(s.graph, path);
  const VtpPolylines back = read_vtp_polylines(path, {"radius_mm"});
  REQUIRE(back.lines.size() == s.graph.branches.size());
  std::size_t k = 0;
  for (std::size_t b = 0; b < s.graph.branches.size(); ++b) {
    const auto& branch = s.graph.branches[b];
    REQUIRE(back.lines[b].size() == branch.points.size());
    for (std::size_t i = 0; i < branch.points.size(); ++i, ++k) {
      CHECK(back.points[static_cast<std::size_t>(back.lines[b][i])] == branch.points[i]);  // bit for bit
      CHECK(back.point_arrays.at("radius_mm")[k] == (i < branch.radii.size() ? branch.radii[i] : 0.0));
    }
  }
}

TEST_CASE("a large mesh spans several compressed blocks and reads back", "[report][vtp]") {
  TriangleMesh m;
  const int n = 3000;  // 3000 x 24 bytes of points: three 32 KiB blocks
  m.V.resize(n, 3);
  m.F.resize(n - 2, 3);
  for (int i = 0; i < n; ++i) m.V.row(i) << std::cos(i * 0.01), std::sin(i * 0.013), i * 0.001;
  for (int i = 0; i + 2 < n; ++i) m.F.row(i) << i, i + 1, i + 2;
  const std::string path = test::scratch_dir("vtp_big") + "/big.vtp";
  write_mesh_vtp(m, path);
  const Vtp v = parse_vtp(path);
  check_consistent(v);
  const auto& pts = v.array("Points", "Points").values;
  REQUIRE(pts.size() == 3u * n);
  for (int i = 0; i < n; i += 97) CHECK(pts[3 * static_cast<std::size_t>(i) + 1] == m.V(i, 1));
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
