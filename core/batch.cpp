#include "batch.h"

#include <mutex>

#include "parallel.h"

namespace accel {

std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads) {
  return trace_all(s, rays, threads, nullptr);
}

std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads, QueryStats* total,
                           const std::atomic<bool>* cancel) {
  std::vector<Hit> hits(rays.size());
  std::mutex total_mutex;
  par::task_arena arena(threads > 0 ? threads : par::task_arena::automatic);
  arena.execute([&] {
    par::parallel_for(par::blocked_range<size_t>(0, rays.size(), 256), [&](const par::blocked_range<size_t>& r) {
      QueryStats local;
      for (size_t i = r.begin(); i != r.end(); ++i) {
        // Every 64 rays: the partitioner's blocks may be far larger than the grain size.
        if ((i - r.begin()) % 64 == 0) {
          par::yield();
          if (cancel && cancel->load(std::memory_order_relaxed)) break;
        }
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
