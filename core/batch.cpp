#include "batch.h"

#include <algorithm>
#include <mutex>
#include <thread>

#include "parallel.h"
#include "student/kit_structure.h"

namespace accel {

bool answered_in_batches(const Structure& s) {
  const auto* kit = dynamic_cast<const KitStructure*>(&s);
  return kit && dynamic_cast<RemoteAnswers*>(kit->student());
}

std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads) {
  return trace_all(s, rays, threads, nullptr);
}

std::vector<Hit> trace_all(const Structure& s, const std::vector<Ray>& rays, int threads, QueryStats* total,
                           const std::atomic<bool>* cancel) {
  // A student's structure whose code runs in a worker process (accelviz-cli's) answers the
  // batch there, on the worker's threads, not one request a ray; `cancel` is looked at
  // before, not during. A worker that fails the batch is asked ray by ray below, where each
  // failure is that ray's miss.
  if (answered_in_batches(s) && !total && !(cancel && cancel->load())) {
    const auto& kit = dynamic_cast<const KitStructure&>(s);
    std::vector<Hit> answers;
    try {
      dynamic_cast<RemoteAnswers*>(kit.student())
          ->time_rays(rays, s.kernel(), threads > 0 ? unsigned(threads) : std::max(1u, std::thread::hardware_concurrency()),
                      &answers);
      for (Hit& h : answers)
        if (h.prim < 0 || size_t(h.prim) >= kit.scene_triangles()) h = Hit{};
      return answers;
    } catch (const std::exception&) {
    }
  }
  std::vector<Hit> hits(rays.size());
  std::mutex total_mutex;
  par::task_arena arena(threads > 0 ? threads : par::task_arena::automatic);
  arena.execute([&] {
    par::parallel_for(par::blocked_range<size_t>(0, rays.size(), 256), [&](const par::blocked_range<size_t>& r) {
      QueryStats local;
      // 64 rays at a time: between them a yield and the cancel check (the partitioner's
      // blocks may be far larger than the grain size), and one intersect_batch() call each.
      for (size_t i = r.begin(); i < r.end(); i += 64) {
        par::yield();
        if (cancel && cancel->load(std::memory_order_relaxed)) break;
        const size_t end = std::min(r.end(), i + 64);
        if (!total) {
          s.intersect_batch(rays.data() + i, end - i, hits.data() + i);
          continue;
        }
        for (size_t k = i; k < end; ++k) {
          QueryStats q;
          hits[k] = s.intersect(rays[k], &q);
          local += q;
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
