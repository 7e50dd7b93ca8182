#pragma once
// Cost heat map: for every pixel of a pinhole camera image, what the primary ray through it
// costs in the structure (nodes or cells visited, or triangles tested), from the real query's
// per-ray counters (QueryStats). Computed in parallel (TBB) over rows; the viewer colour-maps
// it into an overlay, the bench can print it.
#include <atomic>
#include <cstdint>
#include <string_view>
#include <vector>

#include "ray_gen.h"
#include "structure.h"

namespace accel {

/// Which per-ray counter the image shows.
enum class CostMetric : uint8_t {
  NodesVisited,  ///< QueryStats::nodes_visited: nodes entered / grid cells stepped through
  PrimsTested,   ///< QueryStats::prims_tested: ray/triangle tests
};
/// "nodes" / "prims".
std::string_view cost_metric_name(CostMetric m);
/// Parses "nodes" / "prims"; false for anything else.
bool parse_cost_metric(std::string_view name, CostMetric* out);

/// One value per pixel, row by row from the top-left (like primary_rays()).
struct CostImage {
  int width = 0, height = 0;
  CostMetric metric = CostMetric::NodesVisited;
  std::vector<float> values;  ///< width * height counters
  float min_value = 0.0f;     ///< smallest / largest value (0 for an empty image)
  float max_value = 0.0f;
  float p99_value = 0.0f;     ///< 99th percentile: a colour scale outliers do not flatten
  double mean_value = 0.0;
  double compute_ms = 0.0;    ///< wall time of the computation
  bool complete = false;      ///< false when cancelled (values then partly zero)
  float at(int x, int y) const { return values[size_t(y) * size_t(width) + size_t(x)]; }
};

/// The cost of the ray through the centre of every pixel of a w x h image of `camera`
/// (accel::camera_ray, so it matches the viewer's picking), by `metric`, computed with
/// intersect(ray, &stats) in parallel over rows. w or h <= 0 gives an empty image.
CostImage compute_cost_image(const Structure& structure, const PinholeCamera& camera, int w, int h,
                             CostMetric metric);
/// Same; stops early (complete = false) once `*cancel` becomes true. For background threads
/// whose camera has moved on.
CostImage compute_cost_image(const Structure& structure, const PinholeCamera& camera, int w, int h,
                             CostMetric metric, const std::atomic<bool>* cancel);

}  // namespace accel
