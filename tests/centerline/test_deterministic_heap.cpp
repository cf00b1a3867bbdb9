// The allocation scope that makes CGAL's skeletonisation independent of the process's past
// (centerline/deterministic_heap.hpp).
#include <catch2/catch.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "centerline/deterministic_heap.hpp"

using gw::DeterministicHeapScope;

namespace {

// Addresses of a fixed allocation pattern, relative to the first one.
std::vector<std::intptr_t> pattern_offsets() {
  std::vector<std::intptr_t> offsets;
  DeterministicHeapScope scope;
  REQUIRE(scope.active());
  std::vector<std::unique_ptr<int[]>> blocks;
  {
    DeterministicHeapScope::Pause pause;
    blocks.reserve(64);
    offsets.reserve(64);
  }
  for (int i = 0; i < 32; ++i) blocks.emplace_back(new int[1 + (i * 7) % 40]);
  for (int i = 0; i < 32; i += 3) blocks[i].reset();  // freed blocks are reused in LIFO order
  for (int i = 0; i < 16; ++i) blocks.emplace_back(new int[1 + (i * 5) % 40]);
  for (const auto& b : blocks)
    if (b) offsets.push_back(reinterpret_cast<std::intptr_t>(b.get()) - reinterpret_cast<std::intptr_t>(blocks[1].get()));
  return offsets;
}

}  // namespace

TEST_CASE("inside a scope the same allocations get the same relative addresses, whatever the heap held before",
          "[centerline][determinism]") {
  const auto first = pattern_offsets();
  std::vector<std::unique_ptr<char[]>> clutter;
  for (int i = 0; i < 5000; ++i) clutter.emplace_back(new char[8 + (i * 13) % 500]);
  for (int i = 0; i < 5000; i += 2) clutter[i].reset();
  CHECK(pattern_offsets() == first);
}

TEST_CASE("a block that outlives its scope stays valid, and paused allocations use the normal heap",
          "[centerline][determinism]") {
  std::string* survivor = nullptr;
  std::vector<int>* paused = nullptr;
  {
    DeterministicHeapScope scope;
    survivor = new std::string(200, 'x');  // a long string: its buffer is in the region too
    DeterministicHeapScope::Pause pause;
    paused = new std::vector<int>(1000, 7);
  }
  CHECK(gw::deterministic_heap_retained_regions() >= 1);
  CHECK(*survivor == std::string(200, 'x'));
  survivor->append("y");
  delete survivor;
  CHECK(paused->at(999) == 7);
  delete paused;
  // A nested scope on the same thread is inert: the outer one serves it.
  DeterministicHeapScope outer;
  DeterministicHeapScope inner;
  CHECK(outer.active());
  CHECK_FALSE(inner.active());
}

TEST_CASE("the operator new replacement is linked into this test, not carried by the libraries", "[centerline][determinism]") {
  // tests/CMakeLists.txt links gw_deterministic_new into the suites that can extract, as
  // apps/CMakeLists.txt does into the apps; gw_centerline itself no longer holds the replacement (a
  // program without it gets inactive scopes instead of a hijacked allocator).
  CHECK(DeterministicHeapScope::available());
}
