#include "batch.h"

#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace accel {

std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads) {
  return trace_all(s, rays, threads, nullptr);
}

std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads, QueryStats* total,
                           const std::atomic<bool>* cancel) {
  std::vector<Hit> hits(rays.size());
  std::mutex total_mutex;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
      QueryStats local;
      for (size_t i = r.begin(); i != r.end(); ++i) {
        // Every 64 rays: the partitioner's blocks may be far larger than the grain size.
        if (cancel && (i - r.begin()) % 64 == 0 && cancel->load(std::memory_order_relaxed)) break;
        if (total) {
          QueryStats q;
          hits[i] = s.intersect(rays[i], &q);
          local += q;
        } else {
          hits[i] = s.intersect(rays[i]);
        }
      }
      if (total) {
        std::lock_guard lock(total_mutex);
        *total += local;
      }
    });
  });
  return hits;
}

}  // namespace accel
