// The heat map's scale: automatic follows each image's 99th percentile, fixed stays the
// same for two structures' images (so they compare); the histogram counts every pixel.
#include <gtest/gtest.h>

#include <numeric>

#include "built_structure.h"
#include "ray_gen.h"
#include "tools/heatmap_scale.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

accel::CostImage image_of(const std::string& structure) {
  auto scene = test::scene_of("cornell");
  StructureRequest req;
  req.name = structure;
  auto built = build_structure_now(scene, req);
  EXPECT_TRUE(built.ok());
  accel::PinholeCamera cam;
  cam.eye = {1.0f, 1.0f, 3.5f};
  cam.target = {1.0f, 1.0f, 0.0f};
  cam.fovy_deg = 50.0f;
  return accel::compute_cost_image(*built.value()->structure, cam, 48, 32, accel::CostMetric::PrimsTested);
}

TEST(HeatmapScale, AutoFollowsTheImageFixedStaysAcrossStructures) {
  const accel::CostImage grid = image_of("grid"), bvh = image_of("bvh");
  ASSERT_GT(grid.p99_value, 0.0f);
  const HeatmapScale automatic;
  EXPECT_EQ(heatmap_range(automatic, grid).hi, std::max(grid.p99_value, 1.0f));
  EXPECT_EQ(heatmap_range(automatic, bvh).hi, std::max(bvh.p99_value, 1.0f));
  EXPECT_NE(grid.p99_value, bvh.p99_value) << "the two structures cost differently";
  HeatmapScale fixed;
  fixed.fixed = true;
  fixed.lo = 2.0f;
  fixed.hi = 40.0f;
  for (const accel::CostImage* img : {&grid, &bvh}) {
    const ScaleRange r = heatmap_range(fixed, *img);
    EXPECT_EQ(r.lo, 2.0f);
    EXPECT_EQ(r.hi, 40.0f);
  }
}

TEST(HeatmapScale, DifferenceIsPerPixelWithASymmetricScale) {
  const accel::CostImage grid = image_of("grid"), bvh = image_of("bvh");
  std::string error;
  const accel::CostImage d = difference_image(grid, bvh, &error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(d.values.size(), grid.values.size());
  for (size_t i = 0; i < d.values.size(); ++i) EXPECT_EQ(d.values[i], grid.values[i] - bvh.values[i]);
  EXPECT_LT(d.min_value, d.max_value);
  const ScaleRange r = difference_range(HeatmapScale{}, d);
  EXPECT_EQ(r.lo, -r.hi);
  EXPECT_GE(r.hi, 1.0f);
  // A structure against itself: zero everywhere.
  const accel::CostImage same = difference_image(grid, grid, &error);
  for (float v : same.values) EXPECT_EQ(v, 0.0f);
  accel::CostImage small = grid;
  small.width = 1;
  difference_image(grid, small, &error);
  EXPECT_FALSE(error.empty());
}

TEST(HeatmapScale, HistogramCountsEveryPixelInItsBin) {
  accel::CostImage img;
  img.width = 5;
  img.height = 1;
  img.values = {0.0f, 1.0f, 5.0f, 9.99f, 50.0f};
  const std::vector<float> h = cost_histogram(img, {0.0f, 10.0f}, 10);
  ASSERT_EQ(h.size(), 10u);
  EXPECT_EQ(std::accumulate(h.begin(), h.end(), 0.0f), 5.0f);
  EXPECT_EQ(h[0], 1.0f);
  EXPECT_EQ(h[1], 1.0f);
  EXPECT_EQ(h[5], 1.0f);
  EXPECT_EQ(h[9], 2.0f) << "9.99 and the value above the range";
  const std::vector<float> shifted = cost_histogram(img, {2.0f, 10.0f}, 4);
  EXPECT_EQ(shifted[0], 2.0f) << "values below the range count in the first bin";
}

}  // namespace
}  // namespace viz
