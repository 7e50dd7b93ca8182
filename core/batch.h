#pragma once
// Answers many rays in parallel (TBB). Output order is the input order whatever the thread
// count, so results are deterministic.
#include <atomic>
#include <vector>

#include "structure.h"

namespace accel {

/// Closest hit per ray. `threads` <= 0 means all cores.
std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads = 0);
/// A structure whose queries cost a round trip each (a student's, in accelviz-cli: its code
/// runs in a worker process): trace_all() answers its batches in one request, so time it
/// with trace_all, never ray by ray.
bool answered_in_batches(const Structure& s);
/// Same, also summing per-query counters into `total` (may be null). Once `*cancel` is true
/// (checked every 64 rays) the remaining rays are skipped and left as misses: a caller that
/// passes `cancel` discards the result when it is set.
std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads, QueryStats* total,
                           const std::atomic<bool>* cancel = nullptr);

}  // namespace accel
