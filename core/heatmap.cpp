#include "heatmap.h"

#include <algorithm>
#include <chrono>

#include "parallel.h"

namespace accel {

std::string_view cost_metric_name(CostMetric m) {
  switch (m) {
    case CostMetric::NodesVisited: return "nodes";
    case CostMetric::PrimsTested: return "prims";
  }
  return "?";
}

bool parse_cost_metric(std::string_view name, CostMetric* out) {
  if (name == "nodes") *out = CostMetric::NodesVisited;
  else if (name == "prims") *out = CostMetric::PrimsTested;
  else return false;
  return true;
}

CostImage compute_cost_image(const Structure& structure, const PinholeCamera& camera, int w, int h,
                             CostMetric metric) {
  return compute_cost_image(structure, camera, w, h, metric, nullptr);
}

CostImage compute_cost_image(const Structure& structure, const PinholeCamera& camera, int w, int h,
                             CostMetric metric, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  CostImage image;
  image.metric = metric;
  if (w <= 0 || h <= 0) {
    image.complete = true;
    return image;
  }
  image.width = w;
  image.height = h;
  image.values.assign(size_t(w) * size_t(h), 0.0f);
  std::atomic<bool> stopped{false};
  // One task per row: rows cost very different amounts (sky vs. the dense object), so let
  // TBB balance them instead of cutting the image into equal blocks.
  par::parallel_for(par::blocked_range<int>(0, h, 1), [&](const par::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      par::yield();
      if (cancel && cancel->load(std::memory_order_relaxed)) {
        stopped.store(true, std::memory_order_relaxed);
        return;
      }
      float* row = image.values.data() + size_t(y) * size_t(w);
      for (int x = 0; x < w; ++x) {
        const Ray ray = camera_ray(camera, float(x) + 0.5f, float(y) + 0.5f, w, h);
        QueryStats stats;
        structure.intersect(ray, &stats);
        row[x] = float(metric == CostMetric::NodesVisited ? stats.nodes_visited : stats.prims_tested);
      }
    }
  });
  image.complete = !stopped.load();

  const auto [lo, hi] = std::minmax_element(image.values.begin(), image.values.end());
  image.min_value = *lo;
  image.max_value = *hi;
  double sum = 0.0;
  for (float v : image.values) sum += v;
  image.mean_value = sum / double(image.values.size());
  std::vector<float> sorted = image.values;
  const size_t k = std::min(sorted.size() - 1, size_t(0.99 * double(sorted.size())));
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
  image.p99_value = sorted[k];
  image.compute_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace accel
