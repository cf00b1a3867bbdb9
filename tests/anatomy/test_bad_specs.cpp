// Bad specs are refused with a message that names the problem.
#include <catch2/catch.hpp>

#include "anatomy_gen/generate_anatomy.hpp"
#include "anatomy_gen/tree_geometry.hpp"
#include "anatomy_gen/tree_spec.hpp"

namespace {
// Geometry checks only (no meshing): fast.
void check_geometry(const std::string& json) { gw::build_tree_geometry(gw::parse_tree_spec(json)); }

const char* kY = R"({"name": "y", "branches": [
  {"name": "trunk", "points": [[0,0,0],[0,0,30]], "radius": 1.5},
  {"name": "a", "parent": 0, "points": [[0,0,30],[-10,0,45],[-15,0,60]], "radius": 1.5},
  {"name": "b", "parent": 0, "points": [[0,0,30],[10,0,45],[15,0,60]], "radius": 1.5}]})";
}  // namespace

TEST_CASE("a good Y passes the geometry checks", "[anatomy][spec]") { CHECK_NOTHROW(check_geometry(kY)); }

TEST_CASE("a child that does not start on its parent is refused", "[anatomy][spec]") {
  CHECK_THROWS_WITH(check_geometry(R"({"name": "y", "branches": [
      {"name": "trunk", "points": [[0,0,0],[0,0,30]], "radius": 1.5},
      {"name": "stray", "parent": 0, "points": [[3,0,20],[15,0,35]], "radius": 1.5}]})"),
                    Catch::Contains("branch 'stray' starts at") && Catch::Contains("from the centreline of its parent 'trunk'"));
}

TEST_CASE("radius <= 0 and malformed radii are refused", "[anatomy][spec]") {
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "r", "branches": [{"points": [[0,0,0],[0,0,9]], "radius": 0}]})"),
                    Catch::Contains("radius must be > 0"));
  CHECK_THROWS_WITH(
      gw::parse_tree_spec(R"({"name": "r", "branches": [{"points": [[0,0,0],[0,0,9]], "radius": [1, -0.5]}]})"),
      Catch::Contains("radius must be > 0"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "r", "branches": [{"points": [[0,0,0],[0,0,9]], "radius": [1]}]})"),
                    Catch::Contains("radius has 1 values for 2 points"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "r", "branches": [{"points": [[0,0,0],[0,0,9]]}]})"),
                    Catch::Contains("radius is missing"));
}

TEST_CASE("self-intersecting branches are refused", "[anatomy][spec]") {
  // Branch 'b' curls back across the trunk.
  CHECK_THROWS_WITH(check_geometry(R"({"name": "x", "branches": [
      {"name": "trunk", "points": [[0,0,0],[0,0,60]], "radius": 1.5},
      {"name": "a", "parent": 0, "points": [[0,0,60],[-10,0,75]], "radius": 1.5},
      {"name": "b", "parent": 0, "points": [[0,0,60],[15,0,75],[30,0,60],[20,0,38],[0,0,30],[-15,0,30]], "radius": 1.5}]})"),
                    Catch::Contains("branches 'trunk' and 'b' intersect"));
  // One branch looping onto itself.
  CHECK_THROWS_WITH(check_geometry(R"({"name": "loop", "branches": [
      {"name": "coil", "points": [[0,0,0],[0,0,20],[10,0,30],[20,0,20],[10,0,10],[0,1,20],[-5,2,35]], "radius": 1.5}]})"),
                    Catch::Contains("branch 'coil' intersects itself"));
  // Two siblings running into each other.
  CHECK_THROWS_WITH(check_geometry(R"({"name": "cross", "branches": [
      {"name": "trunk", "points": [[0,0,0],[0,0,30]], "radius": 1.5},
      {"name": "a", "parent": 0, "points": [[0,0,30],[-10,0,45],[10,0,75]], "radius": 1.5},
      {"name": "b", "parent": 0, "points": [[0,0,30],[10,0,45],[-10,0,75]], "radius": 1.5}]})"),
                    Catch::Contains("branches 'a' and 'b' intersect"));
}

TEST_CASE("a bend tighter than the tube radius is refused", "[anatomy][spec]") {
  CHECK_THROWS_WITH(check_geometry(R"({"name": "kink", "branches": [
      {"name": "k", "points": [[0,0,0],[0,0,20],[2,0,21],[2,0,0.5]], "radius": 2.0}]})"),
                    Catch::Contains("branch 'k' bends with a curvature radius"));
}

TEST_CASE("structural mistakes are refused with their reason", "[anatomy][spec]") {
  CHECK_THROWS_WITH(gw::parse_tree_spec("{not json"), Catch::Contains("not valid JSON"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"branches": []})"), Catch::Contains("name must be a non-empty string"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "a/b", "branches": []})"), Catch::Contains("name 'a/b'"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "n", "branches": []})"), Catch::Contains("branches must be"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "n", "branches": [
      {"points": [[0,0,0],[0,0,9]], "radius": 1},
      {"parent": 5, "points": [[0,0,9],[0,3,12]], "radius": 1}]})"),
                    Catch::Contains("parent must be the index of an earlier branch"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "n", "branches": [{"points": [[0,0,0]], "radius": 1}]})"),
                    Catch::Contains("at least 2"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "n", "branches": [{"points": [[0,0,0],[0,0,0]], "radius": 1}]})"),
                    Catch::Contains("coincide"));
  CHECK_THROWS_WITH(gw::parse_tree_spec(R"({"name": "n", "units": "m", "branches": [{"points": [[0,0,0],[0,0,1]], "radius": 1}]})"),
                    Catch::Contains("units must be"));
  // A branch continued by a single child is one branch: ambiguous as a bifurcation.
  CHECK_THROWS_WITH(check_geometry(R"({"name": "n", "branches": [
      {"name": "p", "points": [[0,0,0],[0,0,20]], "radius": 1.5},
      {"name": "c", "parent": 0, "points": [[0,0,20],[3,0,40]], "radius": 1.5}]})"),
                    Catch::Contains("ends where a single child starts"));
  // A deformation phase outside [0,1].
  gw::TreeSpec y = gw::parse_tree_spec(kY);
  CHECK_THROWS_WITH(gw::generate_anatomy(y, {false, 1.5}), Catch::Contains("phase"));
}
