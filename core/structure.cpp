#include "structure.h"

#include <chrono>

namespace accel {

void BuildStats::add_leaf(size_t n) {
  constexpr size_t kBuckets = 17;  // 0..15 triangles, then "16 or more"
  if (leaf_size_histogram.empty()) leaf_size_histogram.assign(kBuckets, 0);
  ++leaves;
  if (n == 0) ++empty_leaves;
  max_leaf_size = std::max(max_leaf_size, n);
  ++leaf_size_histogram[std::min(n, kBuckets - 1)];
}

Status Structure::build(const Scene& scene, const ParamSet& params, BuildControl* control) {
  const auto start = std::chrono::steady_clock::now();
  report_progress(control, 0.0);
  auto result = build_impl(scene, params, control);
  if (result) report_progress(control, 1.0);
  build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  refit_ms_ = std::nan("");
  return result;
}

Status Structure::refit(const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  auto result = refit_impl(scene);
  if (result) refit_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Status Structure::refit_impl(const Scene&) {
  return make_error(name() + " cannot refit: rebuild it (only the bounding volume hierarchies keep their topology "
                    "when vertices move)");
}

BuildStats Structure::build_stats() const {
  BuildStats s = compute_stats();
  s.build_ms = build_ms_;
  s.refit_ms = refit_ms_;
  return s;
}

}  // namespace accel
