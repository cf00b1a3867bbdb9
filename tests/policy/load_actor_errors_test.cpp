// load_actor refuses bad files with messages naming the file and the field.
#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "policy/load_actor.hpp"

namespace {

std::string actor(const std::string& format = "\"guidewire-nav/actor/1\"", const std::string& obs_size = "2",
                  const std::string& l0 = R"({"shape": [2, 2], "weight": [1, -1, 0.5, 2], "bias": [0, -1], "activation": "relu"})",
                  const std::string& l1 = R"({"shape": [1, 2], "weight": [1, 1], "bias": [0.5], "activation": "identity"})",
                  const std::string& norm = "null") {
  return "{\"format\": " + format + ", \"obs_size\": " + obs_size +
         ", \"action_size\": 1, \"obs_normalization\": " + norm + ", \"layers\": [" + l0 + ", " + l1 +
         "], \"output\": {\"squash\": \"tanh\", \"low\": [-1], \"high\": [1]}}";
}

void refuses(const std::string& text, const std::string& needle) {
  INFO(text);
  try {
    gw::parse_actor(text, "bad.json");
    FAIL("accepted a bad actor");
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    INFO(msg);
    CHECK(msg.find("bad.json") != std::string::npos);
    CHECK(msg.find(needle) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("the reference actor text is valid", "[policy]") { CHECK_NOTHROW(gw::parse_actor(actor(), "ok.json")); }

TEST_CASE("bad actor files are refused with the field named", "[policy]") {
  refuses("{not json", "invalid JSON");
  refuses(actor("\"guidewire-nav/actor/2\""), "format");
  refuses(actor("\"guidewire-nav/actor/1\"", "3"), "layers[0].shape");  // obs size mismatch
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [2, 2], "weight": [1, -1, 0.5, 2], "bias": [0, -1, 3], "activation": "relu"})"),
          "layers[0].bias");
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [2, 2], "weight": [1, -1, 0.5], "bias": [0, -1], "activation": "relu"})"),
          "layers[0].weight");
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [3, 2], "weight": [1, -1, 0.5, 2, 1, 1], "bias": [0, -1, 1], "activation": "relu"})"),
          "layers[1].shape");  // layer 1 input != layer 0 output
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [2, 2], "weight": [1, -1, 0.5, 2], "bias": [0, -1], "activation": "gelu"})"),
          "layers[0].activation");
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [2, 2], "weight": [1, -1, 0.5, "NaN"], "bias": [0, -1], "activation": "relu"})"),
          "layers[0].weight[3]");
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [2, 2], "weight": [1, -1, 0.5, 2], "bias": [0, -1], "activation": "relu"})",
                R"({"shape": [2, 2], "weight": [1, 1, 1, 1], "bias": [0.5, 1], "activation": "identity"})"),
          "action_size");
  refuses(actor("\"guidewire-nav/actor/1\"", "2",
                R"({"shape": [2, 2], "weight": [1, -1, 0.5, 2], "bias": [0, -1], "activation": "relu"})",
                R"({"shape": [1, 2], "weight": [1, 1], "bias": [0.5], "activation": "identity"})",
                R"({"mean": [0], "var": [1, 1], "clip": 10, "epsilon": 1e-8})"),
          "obs_normalization.mean");
}

TEST_CASE("missing and empty files are refused", "[policy]") {
  CHECK_THROWS_WITH(gw::load_actor("/nonexistent/actor.json"), Catch::Contains("/nonexistent/actor.json"));
  const std::string empty = std::string(GW_BINARY_DIR) + "/empty_actor.json";
  std::ofstream(empty).close();
  CHECK_THROWS_WITH(gw::load_actor(empty), Catch::Contains("empty"));
}

TEST_CASE("act() refuses a wrong observation size", "[policy]") {
  gw::ActorMLP a = gw::parse_actor(actor(), "ok.json");
  CHECK_THROWS_AS(a.act(Eigen::VectorXf::Zero(3)), std::invalid_argument);
}
