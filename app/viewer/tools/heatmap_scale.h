#pragma once
// GL-free: the heat map's colour scale and its histogram. An automatic scale runs from 0 to
// the image's 99th percentile (outliers do not flatten it) and so changes with every image;
// a fixed one keeps [lo, hi] when the structure, the parameters or the view change, so the
// images of a grid and of a BVH compare pixel for pixel.
#include <string>
#include <vector>

#include "heatmap.h"

namespace viz {

struct HeatmapScale {
  bool fixed = false;
  float lo = 0.0f, hi = 1.0f;  ///< the fixed range (used when fixed)
};

struct ScaleRange {
  float lo = 0.0f, hi = 1.0f;  ///< values mapped to the bottom and the top of the colour map
};

/// The range `scale` gives `image`: fixed, or [0, max(p99, 1)].
ScaleRange heatmap_range(const HeatmapScale& scale, const accel::CostImage& image);

/// The difference view: `a` minus `b` per pixel (same size and metric; an error message in
/// `error` otherwise). Its p99_value is the 99th percentile of |a - b|, the half-width of the
/// symmetric diverging scale; min and max are signed.
accel::CostImage difference_image(const accel::CostImage& a, const accel::CostImage& b, std::string* error);
/// The symmetric range of a difference image: [-m, m] with m = max(p99 |a - b|, 1), or the
/// fixed scale's [-hi, hi].
ScaleRange difference_range(const HeatmapScale& scale, const accel::CostImage& diff);

/// Pixel counts of `image` in `bins` equal bins over [range.lo, range.hi]; values outside
/// fall into the first or the last bin, so the counts add up to the pixel count.
std::vector<float> cost_histogram(const accel::CostImage& image, ScaleRange range, int bins);

}  // namespace viz
