// prepare_for_builds() (core/warm_start.h): once called, a large block freed by one phase
// (the loader) serves the next phase's allocation (the build) without new page faults.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>
#include <sstream>
#include <string>

#include "warm_start.h"

namespace accel {
namespace {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

/// Allocates `bytes`, writes one byte per page (the first touch is what faults), frees it.
void touch_and_free(size_t bytes) {
  auto* block = static_cast<volatile char*>(std::malloc(bytes));
  ASSERT_NE(block, nullptr);
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  for (size_t i = 0; i < bytes; i += page) block[i] = 1;
  std::free(const_cast<char*>(block));
}

TEST(WarmStart, AFreedBlockServesTheNextAllocationWithoutPageFaults) {
  if (!builds_reuse_freed_memory()) GTEST_SKIP() << "glibc's allocator only (the sanitizers bring their own)";
  prepare_for_builds();
  constexpr size_t kBytes = 16 << 20;  // like crytek_sponza's build arrays; 4,096 pages
  touch_and_free(kBytes);               // the "loader": faults its pages in once
  const long before = minor_faults();
  touch_and_free(kBytes);               // the "build": the same pages again
  // Without prepare_for_builds() the first block is unmapped on free and the second one
  // takes fresh zeroed pages: ~4,096 faults. A few are allowed for the allocator's own use.
  EXPECT_LT(minor_faults() - before, 64);
}

/// The VmFlags line of the mapping holding `address` in /proc/self/smaps ("" if none).
std::string vm_flags_at(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream header(line);
    if (header >> std::hex >> lo >> dash >> hi && dash == '-') {  // a mapping's first line
      inside = lo <= a && a < hi;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return "";
}

TEST(WarmStart, OperatorNewAdvisesLargeBlocksToHugePages) {
  if (!large_blocks_advised_to_huge_pages()) GTEST_SKIP() << "no advice in this build (sanitizers, not Linux)";
  if (access("/sys/kernel/mm/transparent_hugepage/enabled", R_OK) != 0)
    GTEST_SKIP() << "kernel without transparent huge pages";
  constexpr size_t kBytes = 40 << 20;  // above glibc's mmap threshold: a mapping of its own
  // Called directly (a new-expression may be elided): the plain and the over-aligned form.
  void* block = ::operator new(kBytes);
  void* aligned = ::operator new(kBytes, std::align_val_t(64));
  // The middle of each block lies in a whole 2 MiB page, advised: the kernel marks its
  // mapping "hg" (VM_HUGEPAGE), and its first touch faults a 2 MiB page in where it can.
  const std::string flags = vm_flags_at(static_cast<char*>(block) + kBytes / 2);
  const std::string aligned_flags = vm_flags_at(static_cast<char*>(aligned) + kBytes / 2);
  ::operator delete(block);
  ::operator delete(aligned, std::align_val_t(64));
  if (flags.empty() || aligned_flags.empty()) GTEST_SKIP() << "no /proc/self/smaps";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
  EXPECT_NE(aligned_flags.find(" hg"), std::string::npos) << aligned_flags;
}

}  // namespace
}  // namespace accel
