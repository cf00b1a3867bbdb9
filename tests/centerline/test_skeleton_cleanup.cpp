// clean_skeleton's junction merge on hand-made skeletons: two junctions joined by a chain shorter than
// the vessel's radius are one k-way junction when their side branches' openings overlap, two
// bifurcations when they do not (the great vessels off an aortic arch leave 8-26 mm apart from a
// 20-28 mm wide aorta).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <functional>

#include "centerline/skeleton_tree.hpp"

using namespace gw;

namespace {

// A trunk along x (radius 10, x in [-60, 60]) and two side branches leaving it upwards (+y) at
// x = -gap/2 and +gap/2, 60 mm long, of radius `side`. Nodes every 0.5 mm, MCF-like.
RawSkeleton two_side_branches(double gap, double side, std::function<double(const Eigen::Vector3d&)>* radius_at) {
  RawSkeleton raw;
  auto add = [&](const Eigen::Vector3d& p) {
    raw.nodes.push_back({p, p, 1});
    return static_cast<int>(raw.nodes.size()) - 1;
  };
  int left = -1, right = -1, prev = -1;
  for (int i = 0; i <= 240; ++i) {
    const double x = -60.0 + 0.5 * i;
    const int v = add({x, 0, 0});
    if (prev >= 0) raw.edges.push_back({prev, v});
    prev = v;
    if (std::abs(x + gap / 2) < 1e-9) left = v;
    if (std::abs(x - gap / 2) < 1e-9) right = v;
  }
  REQUIRE(left >= 0);
  REQUIRE(right >= 0);
  for (int origin : {left, right}) {
    prev = origin;
    for (int k = 1; k <= 120; ++k) {
      const int v = add(raw.nodes[static_cast<size_t>(origin)].point + Eigen::Vector3d(0, 0.5 * k, 0));
      raw.edges.push_back({prev, v});
      prev = v;
    }
  }
  *radius_at = [side](const Eigen::Vector3d& p) { return p.y() < 10.0 ? 10.0 : side; };
  return raw;
}

}  // namespace

TEST_CASE("two thin side branches of a wide vessel closer than its radius stay two bifurcations", "[centerline]") {
  // 8 mm apart on a radius-10 trunk (closer than one radius: the old rule merged them), radius 2 each:
  // their openings (2 + 2 mm) do not overlap.
  std::function<double(const Eigen::Vector3d&)> radius_at;
  const RawSkeleton raw = two_side_branches(8.0, 2.0, &radius_at);
  const SkeletonTree tree = clean_skeleton(raw, radius_at, {});
  const auto deg = tree.degree();
  CHECK(std::count(deg.begin(), deg.end(), 3) == 2);
  CHECK(std::count(deg.begin(), deg.end(), 1) == 4);
}

TEST_CASE("side branches whose openings overlap merge into one junction", "[centerline]") {
  // The same 8 mm apart, radius 5 each: 5 + 5 > 8, one junction with four arms (a trifurcation's
  // skeleton: two nodes joined by a short chain).
  std::function<double(const Eigen::Vector3d&)> radius_at;
  const RawSkeleton raw = two_side_branches(8.0, 5.0, &radius_at);
  const SkeletonTree tree = clean_skeleton(raw, radius_at, {});
  const auto deg = tree.degree();
  CHECK(std::count(deg.begin(), deg.end(), 4) == 1);
  CHECK(std::count(deg.begin(), deg.end(), 3) == 0);
  CHECK(tree.chains.size() == 4);
}

TEST_CASE("junctions farther apart than the vessel's radius are never merged", "[centerline]") {
  std::function<double(const Eigen::Vector3d&)> radius_at;
  const RawSkeleton raw = two_side_branches(12.0, 5.0, &radius_at);
  const auto deg = clean_skeleton(raw, radius_at, {}).degree();
  CHECK(std::count(deg.begin(), deg.end(), 3) == 2);
}
