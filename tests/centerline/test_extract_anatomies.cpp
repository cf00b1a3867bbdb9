// Accuracy against the generator's ground truth on every anatomy of anatomies/index.json
// (the targets of issue 4): same topology; mean distance to the true centerline <= 5% of
// the local radius, 95th percentile <= 15%; bifurcation centres within one radius;
// mean radius error <= 10%; and the same target numbering as the truth.
#include <catch2/catch.hpp>
#include <cmath>

#include "centerline/extract/anatomy_index.hpp"
#include "centerline/extract/compare_centerlines.hpp"
#include "centerline/extract/extract_centerline.hpp"
#include "engine/mesh/load_mesh.hpp"

using namespace gw;

namespace {

// Extracts `a` with the truth's inlet and checks the targets.
void check_anatomy(const AnatomyEntry& a) {
    INFO("anatomy " << a.set << "/" << a.name);
    const CenterlineGraph truth = read_centerline(a.truth);
    CenterlineOptions options;
    options.inlet = truth.inlet.position;
    const CenterlineGraph graph = extract_centerline(load_valid_mesh(a.mesh), options);
    const CenterlineAccuracy acc = compare_centerlines(graph, truth);
    INFO(accuracy_to_json(acc));
    CHECK(acc.same_topology);
    CHECK(acc.mean_distance <= 0.05);
    CHECK(acc.p95_distance <= 0.15);
    CHECK(acc.max_bifurcation_offset <= 1.0);
    // Held at about twice the achieved level (MCF's raw skeleton varies from run to run):
    // mean <= 0.0035, p95 <= 0.023, bifurcations <= 0.27 radius (centerline/extract/README.md).
    CHECK(acc.mean_distance <= 0.01);
    CHECK(acc.p95_distance <= 0.05);
    CHECK(acc.max_bifurcation_offset <= 0.5);
    CHECK(acc.mean_radius_error <= 0.10);
    // Target k of the extraction is target k of the truth (the numbering rule depends on
    // geometry only): within two radii of it. Targets whose true path lengths tie within
    // 2 mm (mirror-symmetric trees) may come in either order, since the rule breaks the
    // tie by coordinates and extraction moves ends by a fraction of a millimetre.
    REQUIRE(graph.targets.size() == truth.targets.size());
    for (size_t k = 0; k < truth.targets.size(); ++k) {
      INFO("target " << truth.targets[k].id);
      CHECK(graph.targets[k].id == truth.targets[k].id);
      const double length = plan_path(truth, truth.targets[k].id).length;
      bool matched = false;
      for (const auto& t : truth.targets)
        if (std::abs(plan_path(truth, t.id).length - length) < 2.0 &&
            (graph.targets[k].position - t.position).norm() <= 2.0 * t.radius)
          matched = true;
      CHECK(matched);
    }
}

}  // namespace

TEST_CASE("every anatomy of the set meets the accuracy targets against its ground truth", "[centerline][anatomy]") {
  const auto anatomies = read_anatomy_index(std::string(GW_SOURCE_DIR) + "/anatomies/index.json");
  REQUIRE(!anatomies.empty());
  for (const auto& a : anatomies) check_anatomy(a);
}

TEST_CASE("without --inlet the widest terminal is the inlet", "[centerline][anatomy]") {
  // The coronary-like trees narrow distally, so their inlet is the widest end.
  const auto anatomies = read_anatomy_index(std::string(GW_SOURCE_DIR) + "/anatomies/index.json");
  int checked = 0;
  for (const auto& a : anatomies) {
    const CenterlineGraph truth = read_centerline(a.truth);
    bool widest = true;
    for (const auto& t : truth.targets) widest = widest && t.radius < 0.9 * truth.inlet.radius;
    if (!widest) continue;
    INFO("anatomy " << a.name);
    const CenterlineGraph graph = extract_centerline(load_valid_mesh(a.mesh));
    CHECK((graph.inlet.position - truth.inlet.position).norm() <= truth.inlet.radius);
    ++checked;
  }
  if (checked == 0) WARN("no anatomy with a clearly widest inlet in the index");
}
