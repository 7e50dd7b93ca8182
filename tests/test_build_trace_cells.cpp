// Hand-checked construction steps (build_trace.h) of the uniform grid and the octree on
// tiny scenes: every event in order, with its cells, node ids and leaf reasons, plus the
// octree's depth-limited recording on a bigger scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "build_replay.h"
#include "random.h"
#include "registry.h"
#include "scene.h"
#include "structures/octree.h"
#include "structures/uniform_grid.h"

namespace accel {
namespace {

using Kind = BuildEventKind;

Scene make_scene(std::vector<Vec3> p, std::vector<UVec3> t) { return Scene(std::move(p), std::move(t), "tiny"); }

/// Builds `structure` with `params`, recording every step; the built structure is kept in *out.
BuildTrace record(const std::string& structure, const Scene& scene, const std::vector<std::string>& params,
                  std::unique_ptr<Structure>* out = nullptr, int depth_limit = std::numeric_limits<int>::max()) {
  BuildRecorder recorder(depth_limit);
  auto built = build_structure(structure, scene, params, Kernel::Watertight, nullptr, &recorder);
  EXPECT_TRUE(built) << built.error().message;
  if (built && out) *out = std::move(built.value());
  return recorder.take();
}

std::vector<Kind> kinds(const BuildTrace& t) {
  std::vector<Kind> k;
  for (const BuildEvent& e : t.events) k.push_back(e.kind);
  return k;
}

std::vector<uint32_t> list_of(const BuildTrace& t, const BuildEvent& e) {
  return std::vector<uint32_t>(t.list(e), t.list(e) + e.list_count);
}

void expect_box(const Aabb& b, Vec3 lo, Vec3 hi) {
  EXPECT_EQ(b.min, lo);
  EXPECT_EQ(b.max, hi);
}

// [SECTION] Grid

/// In the plane z = 0, box [0,2]x[0,2]: triangle 0 in cell (0,0) only; triangle 1 is
/// degenerate (not inserted); triangle 2 in the upper right corner, its box covers all four
/// cells of res=2,2,1 but the triangle (x + y >= 2.5) misses cell (0,0) = [0,1]^2.
Scene grid_scene() {
  return make_scene({{0, 0, 0}, {0.8f, 0, 0}, {0, 0.8f, 0},     // 0: in cell 0
                     {0, 0, 0}, {1, 1, 0}, {2, 2, 0},           // 1: collinear, degenerate
                     {0.5f, 2, 0}, {2, 2, 0}, {2, 0.5f, 0}},    // 2: cells 1, 2, 3 (box: 0..3)
                    {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
}

void expect_grid_steps(const std::string& insert, const std::vector<uint32_t>& cells_of_2) {
  SCOPED_TRACE("insert=" + insert);
  const Scene scene = grid_scene();
  ASSERT_EQ(scene.valid_prims(), (std::vector<uint32_t>{0, 2}));
  const BuildTrace t = record("grid", scene, {"res=2,2,1", "insert=" + insert});
  ASSERT_EQ(kinds(t), (std::vector<Kind>{Kind::SceneBox, Kind::GridResolution, Kind::GridInsert, Kind::GridInsert,
                                         Kind::Done}));
  expect_box(t.events[0].box, {0, 0, 0}, {2, 2, 0});
  const BuildEvent& r = t.events[1];
  expect_box(r.box, {0, 0, 0}, {2, 2, 0});
  EXPECT_EQ(r.a, 2u);
  EXPECT_EQ(r.b, 2u);
  EXPECT_EQ(r.count, 1u);
  // Explicit res: only N applies.
  EXPECT_TRUE(std::isnan(r.values[0]));
  EXPECT_EQ(r.values[1], 2.0f);
  EXPECT_TRUE(std::isnan(r.values[2]));
  EXPECT_TRUE(std::isnan(r.values[3]));

  const BuildEvent& a = t.events[2];
  EXPECT_EQ(a.prim, 0u);
  EXPECT_EQ(std::vector<int>(a.lo, a.lo + 3), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(std::vector<int>(a.hi, a.hi + 3), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(list_of(t, a), (std::vector<uint32_t>{0}));
  const BuildEvent& b = t.events[3];
  EXPECT_EQ(b.prim, 2u);
  EXPECT_EQ(std::vector<int>(b.lo, b.lo + 3), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(std::vector<int>(b.hi, b.hi + 3), (std::vector<int>{1, 1, 0}));
  EXPECT_EQ(list_of(t, b), cells_of_2);
  EXPECT_EQ(t.events[4].count, 4u);

  BuildReplay replay(t);
  replay.seek(replay.steps());
  const ReplayGrid& g = replay.grid();
  ASSERT_EQ(g.cells.size(), 4u);
  EXPECT_EQ(g.cells[0], cells_of_2.front() == 0 ? (std::vector<uint32_t>{0, 2}) : (std::vector<uint32_t>{0}));
  for (uint32_t c = 1; c < 4; ++c) EXPECT_EQ(g.cells[c], (std::vector<uint32_t>{2}));
}

TEST(BuildTraceCells, GridBboxStoresTheWholeBoxRange) { expect_grid_steps("bbox", {0, 1, 2, 3}); }

TEST(BuildTraceCells, GridExactRejectsTheCellTheTriangleMisses) { expect_grid_steps("exact", {1, 2, 3}); }

/// Box [0,4]x[0,2]x[0,1] (volume 8), N = 2, lambda = 2: lambda^3 * N = 16 cells, cells per
/// unit length (16 / 8)^(1/3) = 2^(1/3) = 1.2599, so 4*1.26 = 5.04 -> 5, 2.52 -> 3, 1.26 -> 1.
TEST(BuildTraceCells, GridCbrtRuleNumbers) {
  const Scene scene = make_scene({{0, 0, 0}, {4, 0, 0}, {0, 2, 0}, {4, 2, 1}, {0, 2, 1}, {4, 0, 1}},
                                 {{0, 1, 2}, {3, 4, 5}});
  const BuildTrace t = record("grid", scene, {"resolution=cbrt", "lambda=2", "insert=bbox"});
  ASSERT_GE(t.events.size(), 5u);
  const BuildEvent& r = t.events[1];
  ASSERT_EQ(r.kind, Kind::GridResolution);
  expect_box(r.box, {0, 0, 0}, {4, 2, 1});
  EXPECT_EQ(r.values[0], 2.0f);
  EXPECT_EQ(r.values[1], 2.0f);
  EXPECT_EQ(r.values[2], 8.0f);
  EXPECT_NEAR(r.values[3], std::cbrt(2.0), 1e-6);
  EXPECT_EQ(r.a, 5u);
  EXPECT_EQ(r.b, 3u);
  EXPECT_EQ(r.count, 1u);
  // Both triangles' boxes span all 5x3 cells in x and y (one slab in z): every cell, in order.
  std::vector<uint32_t> all(15);
  for (uint32_t c = 0; c < 15; ++c) all[c] = c;
  ASSERT_EQ(t.events[2].kind, Kind::GridInsert);
  EXPECT_EQ(t.events[2].prim, 0u);
  EXPECT_EQ(list_of(t, t.events[2]), all);
  EXPECT_EQ(t.events[3].prim, 1u);
  EXPECT_EQ(list_of(t, t.events[3]), all);
  EXPECT_EQ(t.events[4].kind, Kind::Done);
  EXPECT_EQ(t.events[4].count, 15u);
}

TEST(BuildTraceCells, GridAvgSizeRuleHasNoVolumeOrCubeRoot) {
  const Scene scene = grid_scene();
  const BuildTrace t = record("grid", scene, {"resolution=avgsize", "lambda=1.5"});
  ASSERT_GE(t.events.size(), 2u);
  const BuildEvent& r = t.events[1];
  ASSERT_EQ(r.kind, Kind::GridResolution);
  EXPECT_EQ(r.values[0], 1.5f);
  EXPECT_EQ(r.values[1], 2.0f);
  EXPECT_TRUE(std::isnan(r.values[2]));
  EXPECT_TRUE(std::isnan(r.values[3]));
}

// [SECTION] Octree

/// Root cube [0,4]^3 (mid 2): triangles 0 and 2 in octant 0, triangle 1 in octant 7; inside
/// octant 0 ([0,2]^3, mid 1) triangle 0 is in its octant 0, triangle 2 in its octant 7.
Scene octree_scene() {
  return make_scene({{0, 0, 0}, {0.8f, 0, 0}, {0, 0.8f, 0},                 // 0: near the origin
                     {4, 4, 4}, {3, 4, 4}, {4, 3, 4},                       // 1: near (4,4,4)
                     {1.5f, 1.5f, 1.5f}, {1.9f, 1.5f, 1.5f}, {1.5f, 1.9f, 1.5f}},  // 2: in [1,2]^3
                    {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
}

struct Step {
  Kind kind;
  uint32_t node;
  std::vector<uint32_t> list;  // Node: triangles, Subdivide: children, Leaf: triangles
  uint32_t parent = kNoBuildNode;
  LeafReason reason = LeafReason::FewPrims;
};

void expect_steps(const BuildTrace& t, const std::vector<Step>& want) {
  ASSERT_EQ(t.events.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE("step " + std::to_string(i) + ": " + describe_build_event(t, t.events[i]));
    const BuildEvent& e = t.events[i];
    const Step& w = want[i];
    EXPECT_EQ(e.kind, w.kind);
    if (w.kind == Kind::SceneBox) continue;
    if (w.kind == Kind::Done) {
      EXPECT_EQ(e.count, w.node);
      continue;
    }
    EXPECT_EQ(e.node, w.node);
    EXPECT_EQ(list_of(t, e), w.list);
    if (w.kind == Kind::Node) {
      EXPECT_EQ(e.parent, w.parent);
    }
    if (w.kind == Kind::Leaf) {
      EXPECT_EQ(e.reason, w.reason);
    }
  }
}

/// The 8 children of `first`.. in octant order.
std::vector<uint32_t> block(uint32_t first) {
  std::vector<uint32_t> ids(8);
  for (uint32_t k = 0; k < 8; ++k) ids[k] = first + k;
  return ids;
}

TEST(BuildTraceCells, OctreeStepsDepthFirstChildZeroFirst) {
  const Scene scene = octree_scene();
  std::unique_ptr<Structure> built;
  const BuildTrace t = record("octree", scene, {"max_prims=1", "ct=0"}, &built);
  const auto few = LeafReason::FewPrims;
  std::vector<Step> want = {{Kind::SceneBox, 0, {}},
                            {Kind::Node, 0, {0, 1, 2}},
                            {Kind::Subdivide, 0, block(1)},
                            {Kind::Node, 1, {0, 2}, 0},
                            {Kind::Subdivide, 1, block(9)},
                            {Kind::Node, 9, {0}, 1},
                            {Kind::Leaf, 9, {0}, kNoBuildNode, few}};
  for (uint32_t id = 10; id <= 15; ++id) {  // node 1's empty octants 1..6
    want.push_back({Kind::Node, id, {}, 1});
    want.push_back({Kind::Leaf, id, {}, kNoBuildNode, few});
  }
  want.push_back({Kind::Node, 16, {2}, 1});
  want.push_back({Kind::Leaf, 16, {2}, kNoBuildNode, few});
  for (uint32_t id = 2; id <= 7; ++id) {  // the root's empty octants 1..6
    want.push_back({Kind::Node, id, {}, 0});
    want.push_back({Kind::Leaf, id, {}, kNoBuildNode, few});
  }
  want.push_back({Kind::Node, 8, {1}, 0});
  want.push_back({Kind::Leaf, 8, {1}, kNoBuildNode, few});
  want.push_back({Kind::Done, 17, {}});
  expect_steps(t, want);

  // Boxes and depths: the root cube, node 1 = its octant 0, node 16 = node 1's octant 7.
  expect_box(t.events[1].box, {0, 0, 0}, {4, 4, 4});
  EXPECT_EQ(t.events[1].depth, 0);
  expect_box(t.events[3].box, {0, 0, 0}, {2, 2, 2});
  EXPECT_EQ(t.events[3].depth, 1);
  const BuildEvent& n16 = t.events[5 + 2 * 7];
  ASSERT_EQ(n16.node, 16u);
  expect_box(n16.box, {1, 1, 1}, {2, 2, 2});
  EXPECT_EQ(n16.depth, 2);
  expect_box(t.events[3].centroids, scene.centroid(0), scene.centroid(2));
  // The ids are the finished octree's.
  const auto& data = dynamic_cast<const Octree&>(*built).data();
  ASSERT_EQ(data.nodes.size(), 17u);
  EXPECT_EQ(data.nodes[1].first, 9u);
  EXPECT_EQ(data.nodes[16].count, 1u);
  EXPECT_EQ(data.prim_ids[data.nodes[16].first], 2u);
}

TEST(BuildTraceCells, OctreeMaxDepthStop) {
  const Scene scene = octree_scene();
  const BuildTrace t = record("octree", scene, {"max_prims=1", "ct=0", "max_depth=1"});
  const auto few = LeafReason::FewPrims;
  std::vector<Step> want = {{Kind::SceneBox, 0, {}},
                            {Kind::Node, 0, {0, 1, 2}},
                            {Kind::Subdivide, 0, block(1)},
                            {Kind::Node, 1, {0, 2}, 0},
                            {Kind::Leaf, 1, {0, 2}, kNoBuildNode, LeafReason::MaxDepth}};
  for (uint32_t id = 2; id <= 7; ++id) {
    want.push_back({Kind::Node, id, {}, 0});
    want.push_back({Kind::Leaf, id, {}, kNoBuildNode, few});
  }
  want.push_back({Kind::Node, 8, {1}, 0});
  want.push_back({Kind::Leaf, 8, {1}, kNoBuildNode, few});
  want.push_back({Kind::Done, 9, {}});
  expect_steps(t, want);
}

/// Two triangles filling the square [0,4]^2 at z = 0.5 between them, each reaching at least
/// 4 of the root's octants: refs >= 4 * n, so the root is a leaf (no gain).
TEST(BuildTraceCells, OctreeNoGainStop) {
  const Scene scene = make_scene({{0, 0, 0.5f}, {4, 0, 0.5f}, {0, 4, 0.5f}, {4, 4, 0.5f}, {0, 4, 0.5f}, {4, 0, 0.5f}},
                                 {{0, 1, 2}, {3, 4, 5}});
  const BuildTrace t = record("octree", scene, {"max_prims=1"});
  expect_steps(t, {{Kind::SceneBox, 0, {}},
                   {Kind::Node, 0, {0, 1}},
                   {Kind::Leaf, 0, {0, 1}, kNoBuildNode, LeafReason::NoGain},
                   {Kind::Done, 1, {}}});
}

/// 2000 small random triangles: a recorder limited to depth 1 keeps the steps of the root
/// and its children, marks the grandchildren Unrecorded, and the octree is the normal one.
TEST(BuildTraceCells, OctreeDepthLimitedRecording) {
  std::vector<Vec3> p;
  std::vector<UVec3> tris;
  Rng rng(12);
  for (uint32_t i = 0; i < 2000; ++i) {
    const Vec3 c(rng.uniform(), rng.uniform(), rng.uniform());
    for (int k = 0; k < 3; ++k)
      p.push_back(c + Vec3(rng.uniform(-0.02f, 0.02f), rng.uniform(-0.02f, 0.02f), rng.uniform(-0.02f, 0.02f)));
    tris.push_back(UVec3(3 * i, 3 * i + 1, 3 * i + 2));
  }
  const Scene scene(std::move(p), std::move(tris), "soup2000");
  auto normal = build_structure("octree", scene, {});
  ASSERT_TRUE(normal) << normal.error().message;
  std::unique_ptr<Structure> recorded;
  const BuildTrace t = record("octree", scene, {}, &recorded, 1);

  const OctreeData& a = dynamic_cast<const Octree&>(*normal.value()).data();
  const OctreeData& b = dynamic_cast<const Octree&>(*recorded).data();
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes[i].first, b.nodes[i].first) << i;
    ASSERT_EQ(a.nodes[i].count, b.nodes[i].count) << i;
  }
  EXPECT_EQ(a.prim_ids, b.prim_ids);
  EXPECT_EQ(a.depths, b.depths);
  EXPECT_EQ(a.parents, b.parents);

  const int deepest = *std::max_element(a.depths.begin(), a.depths.end());
  ASSERT_GT(deepest, 2);
  EXPECT_EQ(t.coverage(), "recorded to depth 1 of " + std::to_string(deepest));
  size_t unrecorded = 0, nodes = 0;
  for (const BuildEvent& e : t.events) {
    if (e.kind == Kind::Unrecorded) {
      ++unrecorded;
      EXPECT_EQ(e.depth, 2);
    }
    if (e.kind == Kind::Node) {
      ++nodes;
      EXPECT_LE(e.depth, 1);
    }
    if (e.kind == Kind::Leaf || e.kind == Kind::Subdivide) {
      EXPECT_LE(e.depth, 1);
    }
  }
  EXPECT_EQ(nodes, 9u);  // the root and its 8 children
  EXPECT_EQ(unrecorded, 64u);  // every child of the root is split on this scene
  EXPECT_EQ(t.events.front().kind, Kind::SceneBox);
  EXPECT_EQ(t.events.back().kind, Kind::Done);
  EXPECT_EQ(t.events.back().count, a.nodes.size());
}

}  // namespace
}  // namespace accel
