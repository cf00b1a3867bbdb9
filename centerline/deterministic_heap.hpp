#pragma once
// CGAL's mean-curvature-flow skeletonisation keeps its mesh in a Polyhedron_3 and orders edge
// collapses and degeneracy tests in std::sets of handles, i.e. by heap address. The skeleton
// then depended on what the process had allocated before: the first extraction in a process was
// reproducible, the same mesh extracted again after another one moved points by up to 0.8 mm
// (and changed table episodes). While a DeterministicHeapScope is alive, operator new on its
// thread takes memory from a private region in allocation order (size-class free lists, reused
// last-in first-out), so addresses, and with them every address-ordered container, depend only
// on the sequence of allocations, i.e. on the input.
//
// The scope needs the global operator new/delete replaced (deterministic_global_new.cpp: a
// thread-local check on each call; unchanged behaviour outside a scope). That replacement is the
// OBJECT library gw_deterministic_new, linked only into the executables that can extract (the apps
// and test suites that link gw_centerline or gw_runner), never into a library: a program that
// links gw_centerline without it (a Python binding) keeps its own allocator, and its scopes are
// inactive (available() false; results are then correct but not address-independent). Memory
// from a region
// is never handed to another thread's scope. When the scope ends with blocks still alive (a
// lazily created static that outlives the call), the region stays mapped and those blocks stay
// valid; otherwise it is unmapped. If no region can be reserved the scope does nothing (the
// result is then correct but not address-independent).
#include <cstddef>

namespace gw {

class DeterministicHeapScope {
 public:
  DeterministicHeapScope();
  ~DeterministicHeapScope();
  DeterministicHeapScope(const DeterministicHeapScope&) = delete;
  DeterministicHeapScope& operator=(const DeterministicHeapScope&) = delete;

  bool active() const { return region_ != nullptr; }

  // Whether this program links the operator new replacement (gw_deterministic_new).
  static bool available();

  // Inside a scope: allocations of the current thread use the normal heap until this ends
  // (for results that must outlive the scope's region).
  class Pause {
   public:
    Pause();
    ~Pause();
    Pause(const Pause&) = delete;
    Pause& operator=(const Pause&) = delete;

   private:
    void* saved_;
  };

 private:
  void* region_ = nullptr;
};

// Regions kept mapped because blocks outlived their scope (for tests and diagnostics).
int deterministic_heap_retained_regions();

}  // namespace gw
