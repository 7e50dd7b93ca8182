#pragma once
// What a process does once, before its first build, so that the first build runs about as
// fast as the ones after it (issue #31, "cold builds as fast as warm ones").
//
// Measured on crytek_sponza (2 threads): a fresh `accelviz-cli stats` built the BVH in
// ~135 ms, the same build repeated in that process in ~60 ms. The difference was page
// faults, not the build: the loader freed its large buffers, which glibc hands back to the
// kernel at once (blocks above its mmap threshold are unmapped on free), and the build then
// asked for as much again, which the kernel hands out zeroed, a 4 KiB fault at a time
// (6,750 faults in the first build against ~400 in the third; a fault costs ~10 us on this
// virtual machine). With prepare_for_builds() the first build takes ~1,700 faults and
// ~70 ms. TBB's thread start was also looked at (its pool starts at the first parallel
// loop): a warm-up loop on a background thread made no difference measurable here.
// Blocks too large for the heap (a million-triangle scene's arrays) are fresh memory in
// every build; warm_start.cpp's operator new advises them to transparent huge pages, one
// fault per 2 MiB instead of per 4 KiB.
namespace accel {

/// Call once, early in main (before the scene load): freed memory stays in the process for
/// the next allocation instead of going back to the kernel. Does nothing outside glibc
/// (the web build has the browser's allocator).
void prepare_for_builds();

/// Whether prepare_for_builds() tunes the allocator this process really uses: glibc's,
/// outside the sanitizers (which bring their own malloc) and outside the web build.
bool builds_reuse_freed_memory();

/// Whether this build's operator new advises blocks of 2 MiB and more to huge pages (Linux,
/// outside the sanitizers, which bring their own operator new).
bool large_blocks_advised_to_huge_pages();

}  // namespace accel
