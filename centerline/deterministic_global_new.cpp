// The replacement of the global operator new/delete that DeterministicHeapScope needs
// (deterministic_heap.hpp): a thread-local test, then the scope's region or malloc/free.
// Built as the OBJECT library gw_deterministic_new and linked only into executables (apps/,
// tests/): a library that links gw_centerline (a Python binding, a Slicer module) keeps its
// program's allocator, and its scopes stay inactive (correct results, not address-independent).
#include <cstddef>
#include <new>

namespace gw {

void* deterministic_new(std::size_t n);
void* deterministic_new_nothrow(std::size_t n) noexcept;
void* deterministic_new_aligned(std::size_t n, std::size_t align);
void* deterministic_new_aligned_nothrow(std::size_t n, std::size_t align) noexcept;
void deterministic_delete(void* p) noexcept;

// Its presence is what DeterministicHeapScope::available() tests (a weak reference there).
bool deterministic_global_new_linked() { return true; }

}  // namespace gw

void* operator new(std::size_t n) { return gw::deterministic_new(n); }
void* operator new[](std::size_t n) { return gw::deterministic_new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return gw::deterministic_new_nothrow(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return gw::deterministic_new_nothrow(n); }
// Over-aligned types never come from a region (nothing in the skeletonisation uses them).
void* operator new(std::size_t n, std::align_val_t a) {
  return gw::deterministic_new_aligned(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return gw::deterministic_new_aligned(n, static_cast<std::size_t>(a));
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return gw::deterministic_new_aligned_nothrow(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return gw::deterministic_new_aligned_nothrow(n, static_cast<std::size_t>(a));
}

void operator delete(void* p) noexcept { gw::deterministic_delete(p); }
void operator delete[](void* p) noexcept { gw::deterministic_delete(p); }
void operator delete(void* p, std::size_t) noexcept { gw::deterministic_delete(p); }
void operator delete[](void* p, std::size_t) noexcept { gw::deterministic_delete(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { gw::deterministic_delete(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { gw::deterministic_delete(p); }
void operator delete(void* p, std::align_val_t) noexcept { gw::deterministic_delete(p); }
void operator delete[](void* p, std::align_val_t) noexcept { gw::deterministic_delete(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { gw::deterministic_delete(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { gw::deterministic_delete(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { gw::deterministic_delete(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { gw::deterministic_delete(p); }
