#include "warm_start.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>  // defines __GLIBC__ where it applies
#include <new>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// The sanitizers bring their own allocator and operator new (GCC says so by
// __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__, clang by __has_feature): leave both to them.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define ACCEL_SANITIZER_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define ACCEL_SANITIZER_ALLOCATOR 1
#endif
#endif

#if defined(__linux__) && !defined(__EMSCRIPTEN__) && !defined(ACCEL_SANITIZER_ALLOCATOR)
#define ACCEL_HUGE_PAGE_NEW 1
#include <sys/mman.h>
#endif

namespace accel {

void prepare_for_builds() {
#if defined(__GLIBC__)
  // Blocks up to 32 MiB (glibc's ceiling for this setting) come from the heap and return to
  // it when freed, and the heap keeps up to 1 GiB of free memory at its top instead of
  // trimming it, so the first build reuses the pages the loader faulted in, and each rebuild
  // (the viewer rebuilds on every parameter change) those of the build before. Larger blocks
  // (scenes of millions of triangles) are mapped and unmapped one by one; operator new
  // below advises them to huge pages.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

bool builds_reuse_freed_memory() {
#if defined(__GLIBC__) && !defined(ACCEL_SANITIZER_ALLOCATOR)
  return true;
#else
  return false;
#endif
}

bool large_blocks_advised_to_huge_pages() {
#if defined(ACCEL_HUGE_PAGE_NEW)
  return true;
#else
  return false;
#endif
}

}  // namespace accel

#if defined(ACCEL_HUGE_PAGE_NEW)
// The replaceable global operator new (the array and nothrow forms of the standard library
// call this one; operator delete stays the library's free()): a block of at least
// kHugePage bytes (one huge page) is advised to transparent huge pages before anyone touches it.
// Linux enables them for advised memory only by default ("madvise"), and a build's large
// arrays are fresh memory whose first touch faults one 4 KiB page at a time: the million-
// triangle terrain's grid build took ~34,000 faults (a third of its time; ~10 us a fault
// on the virtual machines measured), with the advice ~6,200. The advice covers the whole
// 2 MiB pages inside the block; on memory already in use it changes nothing.
namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;

void advise_huge_pages(void* block, std::size_t size) {
  if (size < kHugePage) return;
  const auto address = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t first = (address + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (address + size) & ~(kHugePage - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // advice only
}
}  // namespace

void* operator new(std::size_t size) {
  void* block = std::malloc(size != 0 ? size : 1);
  if (!block) throw std::bad_alloc();
  advise_huge_pages(block, size);
  return block;
}

// The over-aligned form (the wide BVH's nodes, the octree's triangle records): as the
// library's, aligned_alloc of the size rounded up to the alignment, freed by its free().
void* operator new(std::size_t size, std::align_val_t align) {
  const std::size_t a = std::max(std::size_t(align), sizeof(void*));
  const std::size_t rounded = ((size != 0 ? size : 1) + a - 1) & ~(a - 1);
  void* block = std::aligned_alloc(a, rounded);
  if (!block) throw std::bad_alloc();
  advise_huge_pages(block, rounded);
  return block;
}
#endif
