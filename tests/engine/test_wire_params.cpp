// Wire parameter loading: the shipped JSON, and clear errors naming the file and field.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>

#include "engine/wire/wire_model.hpp"
#include "mechanics_helpers.hpp"

using namespace gw;

namespace {
std::string write_temp(const std::string& text) { return test::write_test_file("wire_params_test.json", text); }
}  // namespace

TEST_CASE("the shipped 0.014 inch wire JSON loads and matches the defaults", "[params]") {
  const WireParams p = load_wire_params(std::string(GW_SOURCE_DIR) + "/engine/wire/coronary_014.json");
  const WireParams d = default_wire_params();
  CHECK(p.length_mm == d.length_mm);
  CHECK(p.tip_curvature_per_mm == d.tip_curvature_per_mm);
  CHECK(p.diameter_mm == d.diameter_mm);
  CHECK(p.young_modulus_kpa == d.young_modulus_kpa);
  CHECK(p.contact_margin_mm == d.contact_margin_mm);
  CHECK(p.contact_slack_mm == d.contact_slack_mm);
  CHECK(p.max_substep_s == d.max_substep_s);
  const WireModel m = make_wire_model(p, 0.01);
  CHECK(m.substeps == 20);
  CHECK(m.arc_from_tip.front() == Approx(310.0));
  CHECK(m.length.back() == Approx(0.5));  // finer elements at the tip
  CHECK(m.length.front() == Approx(2.0));
}

TEST_CASE("bad wire parameter files are refused with the file and field named", "[params]") {
  CHECK_THROWS_WITH(load_wire_params("/nonexistent/wire.json"), Catch::Contains("cannot open"));
  CHECK_THROWS_WITH(load_wire_params(write_temp("{\"diameter_mm\": -1}")), Catch::Contains("diameter_mm"));
  CHECK_THROWS_WITH(load_wire_params(write_temp("{\"diameter_mm\": \"thin\"}")), Catch::Contains("must be a number"));
  CHECK_THROWS_WITH(load_wire_params(write_temp("{\"diametre_mm\": 0.3}")), Catch::Contains("unknown field 'diametre_mm'"));
  CHECK_THROWS_WITH(load_wire_params(write_temp("[1, 2]")), Catch::Contains("expected a JSON object"));
  CHECK_THROWS_WITH(load_wire_params(write_temp("{oops")), Catch::Contains("not valid JSON"));
  CHECK_THROWS_WITH(make_wire_model(default_wire_params(), 0.0), Catch::Contains("dt"));
}
