// Femoral access on an aortic arch (base/graph/descending_aorta_inlet.hpp): extracted from its widest end (the
// ascending aorta), the generator's Type I-III arches are recognised and entered at the descending aorta, where
// their ground truth enters; no tree of the navigation set is taken for an arch; nearly equal aortic ends make
// the choice a guess, and a great vessel as wide as the aorta makes no arch.
#include <catch2/catch.hpp>
#include <string>

#include "anatomy_gen/generate_anatomy.hpp"
#include "base/graph/anatomy_index.hpp"
#include "base/graph/descending_aorta_inlet.hpp"
#include "centerline/extract_centerline.hpp"

using namespace gw;

namespace {

constexpr double kWideVesselMm = 4.0;  // TaskConfig::wide_vessel_radius_mm's default

}  // namespace

TEST_CASE("an aortic arch extracted from its widest end is entered at the descending aorta", "[centerline][anatomy]") {
  for (int type : {1, 2, 3}) {
    INFO("arch type " << type);
    const std::string spec =
        std::string(GW_SOURCE_DIR) + "/anatomies/segmentation/arch_type" + std::to_string(type) + ".spec.json";
    const GeneratedAnatomy arch = generate_anatomy(read_tree_spec(spec), AnatomyOptions{});
    CenterlineGraph widest = extract_centerline(arch.mesh);  // no inlet: the widest end, the ascending aorta
    REQUIRE((widest.inlet.position - arch.truth.inlet.position).norm() > 50.0);
    const auto access = descending_aorta_inlet(widest, kWideVesselMm);
    REQUIRE(access);
    CHECK((access->position - arch.truth.inlet.position).norm() <= 0.5 * arch.truth.inlet.radius);
    CHECK(access->great_vessels == 3);
    CHECK_FALSE(access->doubtful);
    CHECK(access->note.find("--inlet") != std::string::npos);
    // Extracted again from there: the truth's inlet, and no second switch.
    CenterlineOptions options;
    options.inlet = access->position;
    const CenterlineGraph entered = extract_centerline(arch.mesh, options);
    CHECK((entered.inlet.position - arch.truth.inlet.position).norm() <= 0.5 * arch.truth.inlet.radius);
    CHECK_FALSE(descending_aorta_inlet(entered, kWideVesselMm));
    // Aortic ends nearly as wide: the same end, said to be a guess.
    CenterlineGraph alike = widest;
    alike.inlet.radius = 1.05 * access->radius;
    const auto guess = descending_aorta_inlet(alike, kWideVesselMm);
    REQUIRE(guess);
    CHECK(guess->doubtful);
    CHECK(guess->note.find("guess") != std::string::npos);
    // A great vessel as wide as the narrower aortic end (an iliac fork's two legs, say): no arch.
    CenterlineGraph fork = widest;
    for (Terminal& t : fork.targets)
      if (t.id != access->target && t.radius > 4.5) t.radius = 0.9 * access->radius;
    CHECK_FALSE(descending_aorta_inlet(fork, kWideVesselMm));
  }
}

TEST_CASE("no tree of the navigation set is taken for an aortic arch", "[centerline][anatomy]") {
  const auto anatomies = read_anatomy_index(std::string(GW_SOURCE_DIR) + "/anatomies/index.json");
  REQUIRE(!anatomies.empty());
  for (const auto& a : anatomies) {
    INFO("anatomy " << a.name);
    CHECK_FALSE(descending_aorta_inlet(read_centerline(a.truth), kWideVesselMm));
  }
}
