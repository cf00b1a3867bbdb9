// One mesh, one graph: extraction must not depend on what ran before it in the process
// (evaluate extracts a dozen anatomies and runs thousands of episodes in one process, navigate
// one; a graph that moved by a fraction of a millimetre changed whole episodes of the table).
#include <catch2/catch.hpp>

#include "base/graph/anatomy_index.hpp"
#include "centerline/extract_centerline.hpp"
#include "base/mesh/load_mesh.hpp"

using namespace gw;

namespace {

double max_difference(const CenterlineGraph& a, const CenterlineGraph& b) {
  if (a.branches.size() != b.branches.size()) return 1e9;
  double worst = 0.0;
  for (size_t i = 0; i < a.branches.size(); ++i) {
    if (a.branches[i].points.size() != b.branches[i].points.size()) return 1e9;
    for (size_t p = 0; p < a.branches[i].points.size(); ++p)
      worst = std::max(worst, (a.branches[i].points[p] - b.branches[i].points[p]).norm());
  }
  return worst;
}

}  // namespace

TEST_CASE("extraction gives the same graph whatever was extracted before it in the process",
          "[centerline][determinism]") {
  AnatomyEntry coronary, other;
  for (const auto& a : read_anatomy_index(std::string(GW_SOURCE_DIR) + "/anatomies/index.json")) {
    if (a.name == "coronary") coronary = a;
    if (a.name == "unseen_4_bifurcations") other = a;
  }
  REQUIRE(!coronary.name.empty());
  REQUIRE(!other.name.empty());
  CenterlineOptions options;
  options.inlet = read_centerline(coronary.truth).inlet.position;
  const TriangleMesh mesh = load_valid_mesh(coronary.mesh);
  const CenterlineGraph first = extract_centerline(mesh, options);
  extract_centerline(load_valid_mesh(other.mesh));
  const CenterlineGraph again = extract_centerline(mesh, options);
  CHECK(max_difference(first, again) == 0.0);
}
