#include "tools/heatmap_scale.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace viz {

ScaleRange heatmap_range(const HeatmapScale& scale, const accel::CostImage& image) {
  if (scale.fixed) return {scale.lo, std::max(scale.hi, scale.lo + 1e-6f)};
  return {0.0f, std::max(image.p99_value, 1.0f)};
}

accel::CostImage difference_image(const accel::CostImage& a, const accel::CostImage& b, std::string* error) {
  accel::CostImage d;
  if (a.width != b.width || a.height != b.height || a.metric != b.metric || a.values.size() != b.values.size()) {
    if (error) *error = "the two cost images differ in size or metric";
    return d;
  }
  d.width = a.width;
  d.height = a.height;
  d.metric = a.metric;
  d.complete = a.complete && b.complete;
  d.compute_ms = a.compute_ms + b.compute_ms;
  d.values.resize(a.values.size());
  std::vector<float> magnitude(a.values.size());
  double sum = 0.0;
  for (size_t i = 0; i < a.values.size(); ++i) {
    d.values[i] = a.values[i] - b.values[i];
    magnitude[i] = std::fabs(d.values[i]);
    sum += d.values[i];
  }
  if (!d.values.empty()) {
    const auto [lo, hi] = std::minmax_element(d.values.begin(), d.values.end());
    d.min_value = *lo;
    d.max_value = *hi;
    d.mean_value = sum / static_cast<double>(d.values.size());
    const size_t k = std::min(magnitude.size() - 1, static_cast<size_t>(0.99 * static_cast<double>(magnitude.size())));
    std::nth_element(magnitude.begin(), magnitude.begin() + static_cast<std::ptrdiff_t>(k), magnitude.end());
    d.p99_value = magnitude[k];
  }
  return d;
}

ScaleRange difference_range(const HeatmapScale& scale, const accel::CostImage& diff) {
  const float m = scale.fixed ? std::max(scale.hi, 1e-6f) : std::max(diff.p99_value, 1.0f);
  return {-m, m};
}

std::vector<float> cost_histogram(const accel::CostImage& image, ScaleRange range, int bins) {
  std::vector<float> counts(static_cast<size_t>(std::max(bins, 1)), 0.0f);
  const float span = std::max(range.hi - range.lo, 1e-6f);
  const int last = static_cast<int>(counts.size()) - 1;
  for (float v : image.values) {
    const int b = std::clamp(static_cast<int>(std::floor((v - range.lo) / span * static_cast<float>(counts.size()))), 0, last);
    counts[static_cast<size_t>(b)] += 1.0f;
  }
  return counts;
}

}  // namespace viz
