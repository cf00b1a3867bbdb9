// A user's surface as segmentation tools export it (triangles facing into the lumen, in metres)
// is repaired by the intake, every repair is reported, and it navigates like the clean file.
#include <catch2/catch.hpp>
#include <filesystem>

#include "../mesh/mesh_files.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/episode_batch.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "base/mesh/load_mesh.hpp"
#include "task/navigation_task.hpp"
#include "engine/wire/wire_params.hpp"

namespace {

const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& l : lines)
    if (l.find(text) != std::string::npos) return true;
  return false;
}

gw::EpisodeTrace run_scripted(const gw::NavigationAnatomy& nav, int target, std::uint64_t seed) {
  const gw::NavigationTask task = gw::make_navigation_task(gw::TaskConfig{}, gw::default_wire_params(), {nav.anatomy});
  const auto requests = gw::plan_episodes(task, 0, std::to_string(target), 1, seed);
  return gw::run_batch(task, requests, [] { return gw::make_controller("scripted-omega", ""); }, 1, {}).at(0);
}

}  // namespace

TEST_CASE("an inward-facing surface in metres is repaired, reported, and navigates as the clean one", "[runner][intake]") {
  gw::TriangleMesh m = gw::load_mesh(kT1 + ".stl");
  m.F.col(1).swap(m.F.col(2));  // normals into the lumen
  m.V *= 0.001;                 // metres
  const std::string path = gw::test::scratch_path("t1_inward_metres.stl");
  gw::test::write_binary_stl(path, m);

  gw::NavigationAnatomyOptions options;
  options.centerline_path = kT1 + ".truth.json";  // the same graph for both, so only the wall differs
  options.use_cache = false;
  const gw::NavigationAnatomy user = gw::load_navigation_anatomy(path, options);
  CHECK(mentions(user.repairs, "read as metres"));
  CHECK(mentions(user.repairs, "reversed"));
  CHECK(user.intake_report.find("\"flipped\":true") != std::string::npos);
  const gw::NavigationAnatomy clean = gw::load_navigation_anatomy(kT1 + ".stl", options);
  CHECK(clean.repairs.empty());
  CHECK(clean.intake_report.empty());

  const gw::EpisodeTrace a = run_scripted(user, 2, 3), b = run_scripted(clean, 2, 3);
  CHECK(a.outcome == "success");
  CHECK(a.outcome == b.outcome);
  // The walls are the same triangles up to the unit round trip (float STL), so the episodes agree
  // closely, not bit for bit.
  CHECK(std::abs(static_cast<double>(a.time_s.size()) - static_cast<double>(b.time_s.size())) <= 3);
}
