// Same ray, every structure (compare) and the parameter sweep.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <set>

#include "params.h"
#include "registry.h"
#include "tools/compare_model.h"
#include "tools/sweep_model.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using test::scene_of;
using test::sphere_ray;

TEST(Workbench, CompareRunsEveryStructureAndTraversalOnOneRay) {
  auto scene = scene_of("sphere");
  StructureRequest current;
  current.name = "bvh";
  current.params = {"leaf_size=2", "traversal=dfs"};
  std::atomic<bool> cancel{false};
  std::atomic<int> progress{0};
  const auto rows = compare_structures(scene, sphere_ray(), current, cancel, &progress);
  // brute, grid, octree, kdtree, bvh x 3 traversals, spheretree x 3.
  ASSERT_EQ(rows.size(), 10u);
  EXPECT_EQ(progress.load(), 10);
  const accel::Hit reference = rows.front().hit;
  ASSERT_TRUE(reference.valid());
  int current_rows = 0;
  std::set<std::string> labels;
  for (const CompareRow& r : rows) {
    ASSERT_TRUE(r.ok) << r.label << ": " << r.error;
    EXPECT_EQ(r.hit.prim, reference.prim) << r.label;
    EXPECT_NEAR(r.hit.t, reference.t, 1e-4f * reference.t) << r.label;
    EXPECT_GT(r.steps, 0u);
    EXPECT_GT(r.stats.prims_tested, 0u);
    labels.insert(r.label);
    if (r.current) {
      ++current_rows;
      EXPECT_EQ(r.label, "bvh (dfs)");
      EXPECT_EQ(accel::param_value(r.params, "leaf_size"), "2");  // the current parameters kept
    }
  }
  EXPECT_EQ(current_rows, 1);
  EXPECT_TRUE(labels.count("bvh (pqueue)"));
  EXPECT_TRUE(labels.count("spheretree (ordered)"));
  // Brute force tests every triangle.
  EXPECT_EQ(rows.front().stats.prims_tested, scene->valid_prims().size());
  cancel = true;
  EXPECT_TRUE(compare_structures(scene, sphere_ray(), current, cancel).front().error.empty());
}

TEST(Workbench, SweepValuesAndRun) {
  accel::ParamSpec leaf{"leaf_size", accel::ParamSpec::Type::Int, "4", 1, 64, {}, "", accel::ParamValue(4), {}};
  EXPECT_EQ(sweep_values(leaf, 1, 16, 5, true), (std::vector<double>{1, 2, 4, 8, 16}));
  EXPECT_EQ(sweep_values(leaf, 1, 3, 10, false), (std::vector<double>{1, 2, 3}));  // rounded, no duplicates
  EXPECT_EQ(sweep_values(leaf, 0, 1000, 2, false), (std::vector<double>{1, 64}));   // clamped to the range
  accel::ParamSpec lambda{"lambda", accel::ParamSpec::Type::Float, "2", 0.01, 16, {}, "", accel::ParamValue(2.0),
                          {}};
  const auto v = sweep_values(lambda, 0.5, 4.0, 4, false);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_DOUBLE_EQ(v[1], 0.5 + 3.5 / 3.0);

  auto scene = scene_of("sphere");
  SweepRequest r;
  r.base.name = "grid";
  r.param = "lambda";
  r.lo = 0.5;
  r.hi = 2.0;
  r.steps = 3;
  r.camera = accel::default_camera(scene->bounds());
  r.width = 16;
  r.height = 12;
  SweepProgress progress;
  std::atomic<bool> cancel{false};
  ASSERT_TRUE(run_sweep(scene, r, progress, cancel).ok());
  ASSERT_EQ(progress.points.size(), 3u);
  EXPECT_EQ(progress.total, 3);
  for (const SweepPoint& p : progress.points) {
    EXPECT_TRUE(p.ok) << p.error;
    EXPECT_GE(p.build_ms, 0.0);
    EXPECT_GT(p.trace_ms, 0.0);
    EXPECT_GT(p.nodes, 0u);
  }
  EXPECT_LT(progress.points.front().nodes, progress.points.back().nodes);  // more cells with lambda
  r.param = "insert";  // a choice: not sweepable
  EXPECT_FALSE(run_sweep(scene, r, progress, cancel).ok());
}

}  // namespace
}  // namespace viz
