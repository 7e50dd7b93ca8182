#pragma once
// Answers many rays in parallel (TBB). Output order is the input order whatever the thread
// count, so results are deterministic.
#include <vector>

#include "structure.h"

namespace accel {

/// Closest hit per ray. `threads` <= 0 means all cores.
std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads = 0);
/// Same, also summing per-query counters into `total`.
std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads, QueryStats* total);

}  // namespace accel
