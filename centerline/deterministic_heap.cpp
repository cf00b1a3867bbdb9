#include "centerline/deterministic_heap.hpp"

#include <sys/mman.h>

#include <atomic>
#include <initializer_list>
#include <cstdlib>
#include <new>

namespace gw {
namespace {

// Blocks: a 16-byte header (size class, free flag), then the payload (16-byte aligned).
// Classes: 16..1024 bytes in steps of 16, then powers of two up to 2^58.
constexpr std::size_t kHeader = 16;
constexpr int kSmallClasses = 64;
constexpr int kClasses = kSmallClasses + 48;

struct Header {
  int size_class;
  int free;
};

std::size_t class_bytes(int c) { return c < kSmallClasses ? std::size_t(c + 1) * 16 : std::size_t(1) << (c - kSmallClasses + 11); }

struct Region {
  char* base = nullptr;
  char* top = nullptr;  // next never-used byte
  char* end = nullptr;
  std::size_t live = 0;  // blocks handed out and not yet returned by the owning thread
  void* free_list[kClasses] = {};
};

// Blocks start after the Region bookkeeping at the head of the mapping.
constexpr std::size_t kFirstBlock = (sizeof(Region) + 63) / 64 * 64;

// Every region still mapped, so that delete recognises its blocks on any thread.
constexpr int kMaxRegions = 64;
std::atomic<Region*> g_regions[kMaxRegions];
std::atomic<int> g_slots_used{0};  // slots [0, this) may be non-null: delete scans only those
std::atomic<int> g_retained{0};

thread_local Region* t_allocating = nullptr;  // operator new serves from here (null: the heap)
thread_local Region* t_owned = nullptr;       // this thread's live scope (also while paused)

// kClasses when `n` is too large for any class.
int size_class(std::size_t n) {
  if (n <= 1024) return n == 0 ? 0 : static_cast<int>((n + 15) / 16 - 1);
  int p = 11;
  while (p < 58 && (std::size_t(1) << p) < n) ++p;
  return (std::size_t(1) << p) < n ? kClasses : kSmallClasses + (p - 11);
}

void* region_alloc(Region* r, std::size_t n) {
  const int c = size_class(n);
  if (c >= kClasses) return nullptr;
  const std::size_t rounded = class_bytes(c);
  char* payload;
  if (void* f = r->free_list[c]) {
    r->free_list[c] = *static_cast<void**>(f);
    payload = static_cast<char*>(f);
  } else {
    if (static_cast<std::size_t>(r->end - r->top) < rounded + kHeader) return nullptr;
    payload = r->top + kHeader;
    r->top += rounded + kHeader;
  }
  *reinterpret_cast<Header*>(payload - kHeader) = {c, 0};
  ++r->live;
  return payload;
}

bool contains(const Region* r, const void* p) {
  return r && static_cast<const char*>(p) >= r->base && static_cast<const char*>(p) < r->end;
}

// True when `p` came from a region (then it has been dealt with).
bool region_free(void* p) {
  if (contains(t_owned, p)) {
    Region* r = t_owned;
    Header* h = reinterpret_cast<Header*>(static_cast<char*>(p) - kHeader);
    h->free = 1;
    const int c = h->size_class;
    *static_cast<void**>(p) = r->free_list[c];
    r->free_list[c] = p;
    --r->live;
    return true;
  }
  const int used = g_slots_used.load(std::memory_order_acquire);
  for (int i = 0; i < used; ++i)
    if (contains(g_regions[i].load(std::memory_order_acquire), p)) return true;  // another scope's block: kept
  return false;
}

// The standard contract of operator new: retry through the new-handler, else bad_alloc.
template <class Allocate>
void* allocate_or_throw(Allocate allocate) {
  for (;;) {
    if (void* p = allocate()) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* heap_alloc(std::size_t n) {
  return allocate_or_throw([&] { return std::malloc(n ? n : 1); });
}

void* heap_alloc_aligned(std::size_t n, std::size_t align) {
  if (align < sizeof(void*)) align = sizeof(void*);
  const std::size_t size = ((n ? n : 1) + align - 1) / align * align;
  return allocate_or_throw([&] { return std::aligned_alloc(align, size); });
}

template <class Allocate>
void* or_null(Allocate allocate) noexcept {
  try {
    return allocate();
  } catch (...) {
    return nullptr;
  }
}

void* new_block(std::size_t n) {
  if (Region* r = t_allocating)
    if (void* p = region_alloc(r, n)) return p;
  return heap_alloc(n);
}

void delete_block(void* p) noexcept {
  if (p && !region_free(p)) std::free(p);
}

// A retired region keeps only the pages of its surviving blocks in memory.
void release_free_pages(Region* r) {
  const std::size_t page = 4096;
  auto page_of = [&](const char* p) { return r->base + (static_cast<std::size_t>(p - r->base) / page) * page; };
  char* keep_until = r->base + page;  // end of the pages kept so far (the first holds the Region)
  char* block = r->base + kFirstBlock;
  while (block < r->top) {
    const Header* h = reinterpret_cast<const Header*>(block);
    char* next = block + kHeader + class_bytes(h->size_class);
    if (!h->free) {
      char* first = page_of(block);
      if (first > keep_until) madvise(keep_until, static_cast<std::size_t>(first - keep_until), MADV_DONTNEED);
      char* last = page_of(next - 1) + page;
      if (last > keep_until) keep_until = last;
    }
    block = next;
  }
  char* end = page_of(r->top - 1) + page;
  if (end > keep_until) madvise(keep_until, static_cast<std::size_t>(end - keep_until), MADV_DONTNEED);
}

Region* map_region() {
  // Address space only (no memory is committed until touched); smaller if the system refuses.
  for (std::size_t gib : {4, 1}) {
    const std::size_t bytes = gib << 30;
    void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (m == MAP_FAILED) continue;
    Region* r = new (m) Region();
    r->base = static_cast<char*>(m);
    r->end = r->base + bytes;
    r->top = r->base + kFirstBlock;
    return r;
  }
  return nullptr;
}

}  // namespace

// Defined only in deterministic_global_new.cpp (the OBJECT library gw_deterministic_new, linked into
// executables): weak here, so its address is null in a program without the replacement, and the
// reference alone never pulls the replacement out of a library.
bool deterministic_global_new_linked() __attribute__((weak));

void* deterministic_new(std::size_t n) { return new_block(n); }
void* deterministic_new_nothrow(std::size_t n) noexcept {
  return or_null([&] { return new_block(n); });
}
void* deterministic_new_aligned(std::size_t n, std::size_t align) { return heap_alloc_aligned(n, align); }
void* deterministic_new_aligned_nothrow(std::size_t n, std::size_t align) noexcept {
  return or_null([&] { return heap_alloc_aligned(n, align); });
}
void deterministic_delete(void* p) noexcept { delete_block(p); }

bool DeterministicHeapScope::available() { return &deterministic_global_new_linked != nullptr; }

DeterministicHeapScope::DeterministicHeapScope() {
  if (t_owned) return;  // nested: the outer scope already serves this thread
  if (!available()) return;  // operator new is not ours: a region would never be used
  Region* r = map_region();
  if (!r) return;
  for (int i = 0; i < kMaxRegions; ++i) {
    Region* expected = nullptr;
    if (g_regions[i].compare_exchange_strong(expected, r, std::memory_order_acq_rel)) {
      int used = g_slots_used.load(std::memory_order_acquire);
      while (used < i + 1 && !g_slots_used.compare_exchange_weak(used, i + 1, std::memory_order_acq_rel)) {
      }
      region_ = r;
      t_owned = r;
      t_allocating = r;
      return;
    }
  }
  munmap(r->base, static_cast<std::size_t>(r->end - r->base));  // no free slot: run without
}

DeterministicHeapScope::~DeterministicHeapScope() {
  Region* r = static_cast<Region*>(region_);
  if (!r) return;
  t_allocating = nullptr;
  t_owned = nullptr;
  if (r->live > 0) {  // something outlives the call: keep its memory valid for good
    release_free_pages(r);
    g_retained.fetch_add(1, std::memory_order_acq_rel);
    return;
  }
  for (auto& slot : g_regions) {
    Region* expected = r;
    if (slot.compare_exchange_strong(expected, nullptr, std::memory_order_acq_rel)) break;
  }
  munmap(r->base, static_cast<std::size_t>(r->end - r->base));
}

DeterministicHeapScope::Pause::Pause() : saved_(t_allocating) { t_allocating = nullptr; }
DeterministicHeapScope::Pause::~Pause() { t_allocating = static_cast<Region*>(saved_); }

int deterministic_heap_retained_regions() { return g_retained.load(std::memory_order_acquire); }

}  // namespace gw

