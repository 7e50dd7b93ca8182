#pragma once
// Answers many rays in parallel (TBB). Output order is the input order whatever the thread
// count, so results are deterministic.
#include <atomic>
#include <vector>

#include "structure.h"

namespace accel {

/// Closest hit per ray. `threads` <= 0 means all cores.
std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads = 0);
/// Same, also summing per-query counters into `total` (may be null). Once `*cancel` is true
/// (checked every 64 rays) the remaining rays are skipped and left as misses: a caller that
/// passes `cancel` discards the result when it is set.
std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads, QueryStats* total,
                           const std::atomic<bool>* cancel = nullptr);

}  // namespace accel
