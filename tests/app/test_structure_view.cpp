// Structure -> instances: one per node, empty grid cells, unit shapes and the colour map.
#include <gtest/gtest.h>

#include <cmath>

#include "built_structure.h"
#include "registry.h"
#include "structure_view.h"
#include "tools/depth_filter.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using test::scene_of;

// ---------------------------------------------------------------------------------------
// Structure -> instances

TEST(StructureGeometry, OneInstancePerNode) {
  auto scene = scene_of("sphere");
  for (const auto& info : accel::structure_registry()) {
    StructureRequest req;
    req.name = info.name;
    auto built = build_structure_now(scene, req);
    ASSERT_TRUE(built.ok()) << built.error().message;
    const BuiltStructure& b = *built.value();
    size_t listed = 0, inner_with_plane = 0;
    b.structure->for_each_node([&](const accel::NodeView& v) {
      ++listed;
      if (v.split_axis >= 0) ++inner_with_plane;
    });
    const StructureGeometry& g = b.geometry;
    EXPECT_EQ(g.nodes, listed) << info.name;
    EXPECT_EQ(g.boxes.size() + g.spheres.size(), listed) << info.name;
    EXPECT_EQ(g.planes.size(), inner_with_plane) << info.name;
    if (info.name == "spheretree") {
      EXPECT_EQ(g.spheres.size(), listed);
    }
    if (info.name == "kdtree") {
      EXPECT_GT(g.planes.size(), 0u);
    }
    EXPECT_EQ(g.max_depth, b.stats.max_depth) << info.name;
    for (const NodeInstance& n : g.planes) {
      const int axis = int(n.axis);
      EXPECT_EQ(n.lo[axis], n.hi[axis]);  // flat along its axis
    }
  }
}

TEST(StructureGeometry, GridEmptyCellsOnRequest) {
  auto scene = scene_of("stadium");
  StructureRequest req;
  req.name = "grid";
  req.params = {"res=8,4,8"};
  auto sparse = build_structure_now(scene, req);
  ASSERT_TRUE(sparse.ok());
  req.geometry.empty_cells = true;
  auto all = build_structure_now(scene, req);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all.value()->geometry.boxes.size(), 8u * 4u * 8u);
  EXPECT_TRUE(all.value()->geometry.empty_cells_listed);
  EXPECT_LT(sparse.value()->geometry.boxes.size(), all.value()->geometry.boxes.size());
  EXPECT_TRUE(all.value()->geometry.uniform_depth);
  req.geometry.max_empty_cells = 10;  // too many: only the occupied cells
  auto capped = build_structure_now(scene, req);
  ASSERT_TRUE(capped.ok());
  EXPECT_TRUE(capped.value()->geometry.empty_cells_too_many);
  EXPECT_EQ(capped.value()->geometry.boxes.size(), sparse.value()->geometry.boxes.size());
}

TEST(StructureGeometry, UnitShapesAndColourMap) {
  EXPECT_EQ(unit_cube_edges().size(), 24u);
  EXPECT_EQ(unit_sphere_circles(16).size(), 3u * 16u * 2u);
  EXPECT_EQ(unit_square_triangles().size(), 6u);
  for (const glm::vec3& p : unit_sphere_circles(16)) EXPECT_NEAR(glm::length(p), 1.0f, 1e-5f);
  const glm::vec3 lo = turbo(0.15f), hi = turbo(0.95f), mid = turbo(0.5f);
  EXPECT_GT(lo.b, lo.r);   // blue end
  EXPECT_GT(hi.r, hi.b);   // red end
  EXPECT_GT(mid.g, 0.8f);  // green-yellow middle
  std::vector<Segment> segs;
  accel::Aabb box;
  box.min = glm::vec3(0.0f);
  box.max = glm::vec3(1.0f);
  append_box_segments(segs, box, glm::vec4(1.0f), 2.0f);
  EXPECT_EQ(segs.size(), 12u);
  append_box_segments(segs, accel::Aabb{}, glm::vec4(1.0f), 2.0f);  // empty: nothing
  EXPECT_EQ(segs.size(), 12u);
}

// ---------------------------------------------------------------------------------------
// The depth filter and the first view of a large structure

/// A binary tree's geometry: 2^d boxes at each depth d <= max_depth.
StructureGeometry binary_tree(int max_depth) {
  StructureGeometry g;
  for (int d = 0; d <= max_depth; ++d)
    for (int i = 0; i < (1 << d); ++i) {
      NodeInstance n;
      n.depth = static_cast<float>(d);
      n.leaf = d == max_depth ? 1.0f : 0.0f;
      n.prims = 1.0f;
      g.boxes.push_back(n);
    }
  g.max_depth = max_depth;
  g.nodes = g.boxes.size();
  g.uniform_depth = max_depth == 0;
  return g;
}

TEST(DepthFilter, LargeStructuresOpenWithTheirTopLevels) {
  // The bunny's BVH: 75k nodes, 18 levels (here 2^17 - 1 = 131k nodes, 17 levels).
  const StructureGeometry big = binary_tree(16);
  const int d = first_view_depth(big);
  ASSERT_GE(d, 0);
  EXPECT_LT(d, big.max_depth);
  EXPECT_LE((size_t(2) << d) - 1, kReadableNodes);         // what is shown fits the budget
  EXPECT_GT((size_t(4) << d) - 1, kReadableNodes);         // one more level would not
  EXPECT_EQ(first_view_depth(binary_tree(10)), -1);        // 2047 nodes: all of them
  StructureGeometry grid = big;
  grid.uniform_depth = true;
  EXPECT_EQ(first_view_depth(grid), -1);                   // grid cells: all at depth 0

  DepthSettings s;
  fit_depths(s, big);
  EXPECT_EQ(s.filter, DepthFilter::Range);
  EXPECT_EQ(s.lo, 0);
  EXPECT_EQ(s.hi, d);
  EXPECT_TRUE(s.auto_limited);
  const NodeFilter f = node_filter(s);
  EXPECT_EQ(f.depth_min, 0);
  EXPECT_EQ(f.depth_max, d);
  // The next (small) structure: the automatic range goes, all depths again.
  fit_depths(s, binary_tree(5));
  EXPECT_EQ(s.filter, DepthFilter::All);
  EXPECT_EQ(s.hi, 5);
  EXPECT_FALSE(s.auto_limited);
  // A range the user chose stays, clamped to the structure's depth.
  s.filter = DepthFilter::Range;
  s.lo = 2;
  s.hi = 30;
  fit_depths(s, big);
  EXPECT_EQ(s.filter, DepthFilter::Range);
  EXPECT_EQ(s.lo, 2);
  EXPECT_EQ(s.hi, 16);
}

TEST(DepthFilter, TheLevelOfDetailLimitKeepsTheShallowestLevelsWhole) {
  StructureGeometry big = binary_tree(16);  // 131,071 boxes, 2^d at depth d, in depth order
  for (size_t i = 0; i < big.boxes.size(); ++i) big.boxes[i].lo.x = float(i);  // which one it was
  const std::vector<NodeInstance> kept = limit_drawn_nodes(big.boxes, 1000);
  ASSERT_EQ(kept.size(), 1000u);
  std::vector<size_t> per_depth(17, 0);
  float last_at_9 = 0.0f;
  for (const NodeInstance& n : kept) {
    ++per_depth[static_cast<size_t>(n.depth)];
    if (n.depth == 9.0f) last_at_9 = n.lo.x;
  }
  for (int d = 0; d <= 8; ++d) EXPECT_EQ(per_depth[d], size_t(1) << d) << "depth " << d;  // 511 whole
  EXPECT_EQ(per_depth[9], 1000u - 511u);  // the rest of the room from depth 9, none deeper
  for (int d = 10; d <= 16; ++d) EXPECT_EQ(per_depth[d], 0u);
  // Evenly spread over depth 9 (boxes 511..1022): not just its first 489.
  EXPECT_GT(last_at_9, 1000.0f);
  // Under the limit nothing changes; a uniform grid thins out evenly.
  EXPECT_EQ(limit_drawn_nodes(big.boxes, big.boxes.size()).size(), big.boxes.size());
  std::vector<NodeInstance> cells(10000);
  for (size_t i = 0; i < cells.size(); ++i) cells[i].lo = glm::vec3(float(i), 0, 0);
  const auto thinned = limit_drawn_nodes(cells, 100);
  ASSERT_EQ(thinned.size(), 100u);
  EXPECT_LT(thinned.front().lo.x, 100.0f);
  EXPECT_GT(thinned.back().lo.x, 9800.0f);
}

TEST(DepthFilter, FilterOfEachMode) {
  DepthSettings s;
  s.filter = DepthFilter::Leaves;
  EXPECT_TRUE(node_filter(s).leaves_only);
  EXPECT_TRUE(node_filter(s).hide_empty);
  s.empty_cells = true;  // listed empty cells are drawn
  EXPECT_FALSE(node_filter(s).hide_empty);
  s.filter = DepthFilter::One;
  s.one = 3;
  EXPECT_EQ(node_filter(s).depth_min, 3);
  EXPECT_EQ(node_filter(s).depth_max, 3);
}

}  // namespace
}  // namespace viz
