// Accuracy against the generator's ground truth on every anatomy of anatomies/index.json
// (the targets of issue 4): same topology; mean distance to the true centerline <= 5% of
// the local radius, 95th percentile <= 15%; bifurcation centres within one radius;
// mean radius error <= 10%; and the same target numbering as the truth.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "base/graph/anatomy_index.hpp"
#include "centerline/compare_centerlines.hpp"
#include "centerline/extract_centerline.hpp"
#include "anatomy_gen/generate_anatomy.hpp"
#include "base/mesh/load_mesh.hpp"

using namespace gw;

namespace {

// Extracts `a` with the truth's inlet and checks the targets.
void check_anatomy(const AnatomyEntry& a) {
    INFO("anatomy " << a.set << "/" << a.name);
    const CenterlineGraph truth = read_centerline(a.truth);
    CenterlineOptions options;
    options.inlet = truth.inlet.position;
    CenterlineStats stats;
    const CenterlineGraph graph = extract_centerline(load_valid_mesh(a.mesh), options, &stats);
    CHECK(stats.missed_ends == 0);  // every flat end reached by the first skeleton: no graft, no end-driven pass
    const CenterlineAccuracy acc = compare_centerlines(graph, truth);
    INFO(accuracy_to_json(acc));
    CHECK(acc.same_topology);
    CHECK(acc.mean_distance <= 0.05);
    CHECK(acc.p95_distance <= 0.15);
    CHECK(acc.max_bifurcation_offset <= 1.0);
    // Held at about twice the achieved level (margin for changes to the pipeline):
    // mean <= 0.0035, p95 <= 0.023, bifurcations <= 0.27 radius (centerline/README.md).
    CHECK(acc.mean_distance <= 0.01);
    CHECK(acc.p95_distance <= 0.05);
    CHECK(acc.max_bifurcation_offset <= 0.5);
    CHECK(acc.mean_radius_error <= 0.10);
    // Target k of the extraction is target k of the truth (the numbering rule depends on
    // geometry only, with a tolerance for near-ties): its end lies within two radii of it.
    REQUIRE(graph.targets.size() == truth.targets.size());
    for (size_t k = 0; k < truth.targets.size(); ++k) {
      INFO("target " << truth.targets[k].id);
      CHECK(graph.targets[k].id == truth.targets[k].id);
      CHECK((graph.targets[k].position - truth.targets[k].position).norm() <= 2.0 * truth.targets[k].radius);
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
  CHECK(checked > 0);  // the index holds such anatomies (the coronaries); none checked = the test checked nothing
}

TEST_CASE("an open, noisy coronary tree (like a clinical segmentation) meets the accuracy targets",
          "[centerline][anatomy]") {
  // The coronary-like tree with every inlet and outlet left open and each vertex moved up to
  // 0.1 mm (~5-10% of the local radius) at random, as a CT segmentation's surface would be.
  AnatomyEntry entry;
  for (const auto& a : read_anatomy_index(std::string(GW_SOURCE_DIR) + "/anatomies/index.json"))
    if (a.name == "coronary") entry = a;
  REQUIRE(!entry.name.empty());
  AnatomyOptions options;
  options.open_ends = true;
  GeneratedAnatomy anatomy = generate_anatomy(read_tree_spec(entry.spec), options);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1 / std::sqrt(3.0), 0.1 / std::sqrt(3.0));
  for (Eigen::Index i = 0; i < anatomy.mesh.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) anatomy.mesh.V(i, k) += jitter(rng);
  CenterlineOptions extract_options;
  extract_options.inlet = anatomy.truth.inlet.position;
  CenterlineStats stats;
  const CenterlineGraph graph = extract_centerline(anatomy.mesh, extract_options, &stats);
  const CenterlineAccuracy acc = compare_centerlines(graph, anatomy.truth);
  WARN(accuracy_to_json(acc));  // in the log: how far the noise moved the result
  CHECK(stats.capped_holes == static_cast<int>(anatomy.truth.targets.size()) + 1);
  CHECK(stats.missed_ends == 0);  // every capped end reached by the first skeleton
  CHECK(acc.same_topology);
  CHECK(acc.mean_distance <= 0.05);
  CHECK(acc.p95_distance <= 0.15);
  CHECK(acc.max_bifurcation_offset <= 1.0);
  CHECK(acc.mean_radius_error <= 0.10);
  REQUIRE(graph.targets.size() == anatomy.truth.targets.size());
  for (size_t k = 0; k < graph.targets.size(); ++k)
    CHECK((graph.targets[k].position - anatomy.truth.targets[k].position).norm() <= 2.0 * anatomy.truth.targets[k].radius);
}
