// Each topological defect is counted, and unit suspicion is warned about.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "base/mesh/validate_mesh.hpp"
#include "base/mesh/weld_vertices.hpp"
#include "mesh_files.hpp"

using namespace gw;
using Catch::Matchers::Contains;

namespace {
bool any_contains(const std::vector<std::string>& lines, const std::string& word) {
  for (const auto& l : lines)
    if (l.find(word) != std::string::npos) return true;
  return false;
}

TriangleMesh without_faces(const TriangleMesh& m, std::vector<int> drop) {
  TriangleMesh out;
  out.V = m.V;
  out.F.resize(m.F.rows() - static_cast<Eigen::Index>(drop.size()), 3);
  Eigen::Index k = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    if (std::find(drop.begin(), drop.end(), f) == drop.end()) out.F.row(k++) = m.F.row(f);
  return out;
}

TriangleMesh scaled(TriangleMesh m, double s) {
  m.V *= s;
  return m;
}
}  // namespace

TEST_CASE("a closed cube is clean", "[mesh]") {
  const MeshReport r = validate_mesh(scaled(test::unit_cube(), 20.0));
  CHECK(r.ok());
  CHECK(r.warnings.empty());
  CHECK(r.boundary_loops == 0);
  CHECK(r.components == 1);
  CHECK(r.volume == Approx(8000.0));
  CHECK(r.max_extent == Approx(20.0));
}

TEST_CASE("open boundaries are counted as loops", "[mesh]") {
  // Removing both triangles of the z=0 and z=1 sides leaves a tube with two openings.
  const MeshReport r = validate_mesh(scaled(without_faces(test::unit_cube(), {0, 1, 2, 3}), 20.0));
  CHECK(r.boundary_loops == 2);
  CHECK(r.boundary_edges == 8);
  CHECK_FALSE(r.closed());
  CHECK(any_contains(r.warnings, "open"));
}

TEST_CASE("non-manifold edges, components, degenerate faces", "[mesh]") {
  TriangleMesh m = scaled(test::unit_cube(), 20.0);
  const Eigen::Index nv = m.V.rows(), nf = m.F.rows();
  // A second cube far away: two components.
  m.V.conservativeResize(2 * nv + 1, 3);
  m.V.block(nv, 0, nv, 3) = m.V.topRows(nv).rowwise() + Eigen::RowVector3d(100, 0, 0);
  m.V.row(2 * nv) << 10, 10, 50;  // apex of a fin on edge 0-1
  m.F.conservativeResize(2 * nf + 2, 3);
  m.F.block(nf, 0, nf, 3) = m.F.topRows(nf).array() + static_cast<int>(nv);
  m.F.row(2 * nf) << 0, 1, static_cast<int>(2 * nv);  // third face on edge 0-1: non-manifold
  m.F.row(2 * nf + 1) << 2, 2, 3;                     // repeated vertex: degenerate
  const MeshReport r = validate_mesh(m);
  CHECK(r.components == 2);
  CHECK(r.non_manifold_edges >= 1);
  CHECK(r.degenerate_faces == 1);
  CHECK(any_contains(r.warnings, "components"));
  CHECK(any_contains(r.warnings, "non-manifold"));
  CHECK(any_contains(r.warnings, "degenerate"));
}

TEST_CASE("NaN coordinates are an error, not a bounding box", "[mesh]") {
  TriangleMesh m = scaled(test::unit_cube(), 20.0);
  m.V(5, 2) = std::numeric_limits<double>::quiet_NaN();
  m.V(6, 0) = std::numeric_limits<double>::infinity();
  const MeshReport r = validate_mesh(m);
  CHECK(r.non_finite_vertices == 2);
  CHECK_FALSE(r.ok());
  CHECK(any_contains(r.errors, "NaN"));
  CHECK(std::isfinite(r.max_extent));
}

TEST_CASE("sizes that suggest the wrong units are warned about", "[mesh]") {
  CHECK(any_contains(validate_mesh(scaled(test::unit_cube(), 0.15)).warnings, "metres"));
  CHECK(any_contains(validate_mesh(scaled(test::unit_cube(), 3.0)).warnings, "centimetres"));
  CHECK(any_contains(validate_mesh(scaled(test::unit_cube(), 1e5)).warnings, "micrometres"));
  CHECK_FALSE(any_contains(validate_mesh(scaled(test::unit_cube(), 80.0)).warnings, "units"));
}

TEST_CASE("welding merges identical corners and keeps winding", "[mesh]") {
  const TriangleMesh cube = test::unit_cube();
  TriangleMesh soup;  // every face with its own three corners, as STL stores it
  soup.V.resize(3 * cube.F.rows(), 3);
  soup.F.resize(cube.F.rows(), 3);
  for (Eigen::Index f = 0; f < cube.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      soup.V.row(3 * f + c) = cube.V.row(cube.F(f, c));
      soup.F(f, c) = static_cast<int>(3 * f + c);
    }
  const TriangleMesh welded = weld_vertices(soup);
  CHECK(welded.V.rows() == 8);
  CHECK(validate_mesh(welded).closed());
  CHECK(validate_mesh(welded).volume == Approx(1.0));
}

TEST_CASE("report JSON carries the counts", "[mesh]") {
  const std::string j = report_to_json(validate_mesh(scaled(test::unit_cube(), 20.0)));
  CHECK_THAT(j, Contains("\"faces\":12") && Contains("\"closed\":true"));
}
