// ActorMLP: hand-computed outputs, normalisation, and no heap allocation per act() call.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <string>

#include "policy/load_actor.hpp"

// Count every malloc while armed (glibc interposition): Eigen allocates through malloc and
// operator new goes through it too, so this catches any allocation inside act().
extern "C" void* __libc_malloc(std::size_t);
static bool g_count_armed = false;
static long g_malloc_calls = 0;
extern "C" void* malloc(std::size_t n) {
  if (g_count_armed) ++g_malloc_calls;
  return __libc_malloc(n);
}

namespace {

std::string tiny_actor(const std::string& norm = "null") {
  return R"({"format": "guidewire-nav/actor/1", "obs_size": 2, "action_size": 1, "obs_layout": "test/1",
    "obs_normalization": )" + norm + R"(,
    "layers": [
      {"shape": [2, 2], "weight": [1, -1, 0.5, 2], "bias": [0, -1], "activation": "relu"},
      {"shape": [1, 2], "weight": [1, 1], "bias": [0.5], "activation": "identity"}],
    "output": {"squash": "tanh", "low": [-2], "high": [2]},
    "training_settings": {}, "git_commit": null})";
}

}  // namespace

TEST_CASE("tiny actor matches hand-computed values", "[policy]") {
  gw::ActorMLP a = gw::parse_actor(tiny_actor(), "tiny");
  REQUIRE(a.obs_size() == 2);
  REQUIRE(a.action_size() == 1);
  REQUIRE(a.obs_layout() == "test/1");
  // W1 x + b1 = [1-2, 0.5+4-1] = [-1, 3.5] -> relu [0, 3.5]; W2 h + b2 = 4; action = -2 + (tanh 4 + 1)/2 * 4.
  Eigen::VectorXf obs(2);
  obs << 1, 2;
  CHECK(a.act(obs)[0] == Approx(2.0 * std::tanh(4.0)).epsilon(1e-6));
  // Both hidden units off: output 0.5 -> 2 tanh(0.5).
  obs << -1, 0;
  CHECK(a.act(obs)[0] == Approx(2.0 * std::tanh(0.5)).epsilon(1e-6));
}

TEST_CASE("observation normalisation follows VecNormalize", "[policy]") {
  gw::ActorMLP a = gw::parse_actor(
      tiny_actor(R"({"mean": [1, 0], "var": [4, 1], "clip": 1.5, "epsilon": 0})"), "tiny-norm");
  Eigen::VectorXf obs(2);
  obs << 3, 10;  // normalised: (3-1)/2 = 1, clip(10) = 1.5 -> h = relu([-0.5, 0.5+3-1]) = [0, 2.5] -> 3
  CHECK(a.act(obs)[0] == Approx(2.0 * std::tanh(3.0)).epsilon(1e-6));
}

TEST_CASE("act() does not allocate", "[policy]") {
  gw::ActorMLP a = gw::parse_actor(tiny_actor(R"({"mean": [1, 0], "var": [4, 1], "clip": 5, "epsilon": 1e-8})"), "t");
  Eigen::VectorXf obs(2), action(1);
  obs << 0.3f, -0.7f;
  g_malloc_calls = 0;
  void* probe = std::malloc(8);  // proves the counter is live
  g_count_armed = true;
  void* probe2 = std::malloc(8);
  for (int i = 0; i < 100; ++i) a.act(obs, action);
  g_count_armed = false;
  std::free(probe);
  std::free(probe2);
  CHECK(g_malloc_calls == 1);  // only the probe
}
