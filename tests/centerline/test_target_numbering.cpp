// The target-numbering rule (centerline_graph.hpp): path length, with near-ties broken by the
// end's coordinates so that extraction noise of a tenth of a millimetre cannot renumber targets.
#include <catch2/catch.hpp>

#include "base/graph/centerline_graph.hpp"
#include "base/graph/inlet_ambiguity.hpp"

using namespace gw;

namespace {

// A trunk of 10 mm along z with one straight leaf per end point (each leaf leaves from the
// trunk's end), so a leaf's path length is 10 + |end - (0,0,10)|.
CenterlineGraph star(const std::vector<Eigen::Vector3d>& ends) {
  CenterlineGraph g;
  g.branches.push_back({0, -1, {{0, 0, 0}, {0, 0, 10}}, {2, 2}});
  Bifurcation bif{0, {0, 0, 10}, 0, {}};
  for (const auto& e : ends) {
    const int id = static_cast<int>(g.branches.size());
    g.branches.push_back({id, 0, {{0, 0, 10}, e}, {1, 1}});
    bif.children.push_back(id);
  }
  g.bifurcations = {bif};
  g.inlet = {0, {0, 0, 0}, 0, 2.0};
  number_targets(g);
  return g;
}

// The end (x) of target 1, 2, ...
std::vector<double> xs_in_target_order(const CenterlineGraph& g) {
  std::vector<double> xs;
  for (const auto& t : g.targets) xs.push_back(t.position.x());
  return xs;
}

}  // namespace

TEST_CASE("targets are numbered by path length when the lengths differ by more than the tie tolerance",
          "[centerline][numbering]") {
  // Lengths 30 and 31 mm: the longer one has the smaller x but comes second.
  const auto g = star({{-21, 0, 10}, {20, 0, 10}});
  CHECK(xs_in_target_order(g) == std::vector<double>{20, -21});
  CHECK(g.targets[0].id == 1);
  CHECK(g.targets[1].id == 2);
}

TEST_CASE("a near-tie in path length is broken by x whichever end is a hair longer", "[centerline][numbering]") {
  // 119.34 against 119.36 mm was the sensitivity pattern's case: extraction swapped them.
  for (const double delta : {-0.3, -0.02, 0.0, 0.02, 0.3}) {
    INFO("delta " << delta);
    const auto g = star({{20, 0, 10}, {-20 - delta, 0, 10}});
    CHECK(xs_in_target_order(g) == std::vector<double>{-20 - delta, 20});
  }
}

TEST_CASE("ties chain, and ends level in x are ordered by y, then z", "[centerline][numbering]") {
  // Lengths 30.0, 30.4, 30.8 (each within 0.5 mm of the next) form one tie: ordered by x.
  const auto chained = star({{-20, 0, 10}, {0, 20.4, 10}, {20.8, 0, 10}});
  CHECK(xs_in_target_order(chained) == std::vector<double>{-20, 0, 20.8});
  // Two ends 0.5 mm apart in x (less than the 1 mm coordinate tolerance): y decides.
  const auto level = star({{0.5, -20, 10}, {0, 20, 10}});
  REQUIRE(level.targets.size() == 2);
  CHECK(level.targets[0].position.y() == Approx(-20));
  // A shorter third target keeps its place in front of the tie.
  const auto mixed = star({{0, 20, 10}, {0.5, -20, 10}, {0, 0, 15}});
  CHECK(mixed.targets[0].position.z() == Approx(15));
  CHECK(mixed.targets[1].position.y() == Approx(-20));
}

TEST_CASE("the widest-end inlet guess is flagged when a target end is nearly as wide", "[centerline][inlet]") {
  auto g = star({{20, 0, 10}, {-25, 0, 10}});
  g.inlet.radius = 2.0;
  CHECK(inlet_ambiguity(g).empty());  // the leaves' ends have radius 1
  g.targets[1].radius = 1.9;
  const std::string w = inlet_ambiguity(g);
  CHECK(w.find("target 2") != std::string::npos);
  CHECK(w.find("--inlet 0.00,0.00,0.00") != std::string::npos);
}
