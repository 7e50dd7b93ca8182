// Construction steps of the BVH builders of bvh_builders.cpp (median, sah, pca_sah,
// bottom_up, insertion), worked out by hand on scenes of 3 to 4 triangles: the kinds in
// order, node ids, axes, split planes and costs, leaf reasons and lists, merge order,
// insertion paths with their costs and choices.
//
// Every scene is made of "unit triangles": the triangle at corner p has the vertices p,
// p + (1,0,0), p + (0,1,1), so its box is [p, p + 1] (area 6) and its centre p + 0.5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "build_tree_compare.h"
#include "build_trace.h"
#include "scene.h"
#include "structures/bvh_builders.h"

namespace accel {
namespace {

using K = BuildEventKind;

Scene unit_triangles(const std::vector<Vec3>& corners) {
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;
  for (const Vec3& p : corners) {
    const uint32_t v = uint32_t(positions.size());
    positions.push_back(p);
    positions.push_back(p + Vec3(1, 0, 0));
    positions.push_back(p + Vec3(0, 1, 1));
    triangles.push_back(UVec3(v, v + 1, v + 2));
  }
  return Scene(std::move(positions), std::move(triangles), "unit_triangles");
}

Aabb box(Vec3 lo, Vec3 hi) {
  Aabb b;
  b.min = lo;
  b.max = hi;
  return b;
}
/// The box of unit triangles with corners x0..x1 on the x axis: [x0, x1 + 1] x [0, 1]^2.
Aabb xbox(float x0, float x1) { return box(Vec3(x0, 0, 0), Vec3(x1 + 1, 1, 1)); }

void expect_box(const Aabb& got, const Aabb& want, const std::string& what) {
  EXPECT_EQ(got.min, want.min) << what;
  EXPECT_EQ(got.max, want.max) << what;
}

struct Recorded {
  BuildTrace trace;
  BuildTree tree;
};

/// Records a build and checks it made the normal build's tree.
Recorded record(const Scene& scene, const BvhBuildOptions& o) {
  BuildRecorder recorder;
  Recorded r;
  r.tree = build_bvh_tree(scene, o, nullptr, &recorder);
  r.trace = recorder.take();
  const BuildTree normal = build_bvh_tree(scene, o);
  testing::expect_same_tree(normal, r.tree);
  return r;
}

std::vector<K> kinds(const BuildTrace& t) {
  std::vector<K> k;
  for (const BuildEvent& e : t.events) k.push_back(e.kind);
  return k;
}
std::vector<uint32_t> list_of(const BuildTrace& t, const BuildEvent& e) {
  return std::vector<uint32_t>(t.list(e), t.list(e) + e.list_count);
}
std::vector<uint32_t> sorted(std::vector<uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

void expect_node(const BuildTrace& t, const BuildEvent& e, uint32_t id, uint32_t parent, int depth,
                 std::vector<uint32_t> prims_any_order) {
  ASSERT_EQ(e.kind, K::Node);
  EXPECT_EQ(e.node, id);
  EXPECT_EQ(e.parent, parent) << "node " << id;
  EXPECT_EQ(e.depth, depth) << "node " << id;
  EXPECT_EQ(sorted(list_of(t, e)), sorted(prims_any_order)) << "node " << id;
}
void expect_leaf(const BuildTrace& t, const BuildEvent& e, uint32_t id, LeafReason reason,
                 const std::vector<uint32_t>& prims) {
  ASSERT_EQ(e.kind, K::Leaf);
  EXPECT_EQ(e.node, id);
  EXPECT_EQ(e.reason, reason) << "leaf " << id;
  EXPECT_EQ(list_of(t, e), prims) << "leaf " << id;
}
void expect_merge(const BuildEvent& e, uint32_t id, uint32_t a, uint32_t b, const Aabb& want, float cost) {
  ASSERT_EQ(e.kind, K::Merge);
  EXPECT_EQ(e.node, id);
  EXPECT_EQ(e.a, a) << "merge " << id;
  EXPECT_EQ(e.b, b) << "merge " << id;
  expect_box(e.box, want, "merge " + std::to_string(id));
  EXPECT_EQ(e.cost, cost) << "merge " << id;
}

// ----------------------------------------------------------------------------
// Median
// ----------------------------------------------------------------------------

// Corners x = 4, 0, 6, 2 (triangles 0..3), one triangle per leaf, longest axis (always x).
// Pre-order ids: 0 root {0..3}, 1 = {1, 3} (x 0, 2), 2 = {1}, 3 = {3}, 4 = {0, 2} (x 4, 6),
// 5 = {0}, 6 = {2}. Planes halfway between the last left and first right centre.
TEST(BuildTraceBvh, MedianStepsByLongestAxis) {
  const Scene scene = unit_triangles({{4, 0, 0}, {0, 0, 0}, {6, 0, 0}, {2, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::Median;
  o.axis = MedianAxis::Longest;
  o.leaf_size = 1;
  const Recorded r = record(scene, o);
  const BuildTrace& t = r.trace;
  const std::vector<K> want = {K::SceneBox, K::Node, K::Axis, K::Split,                    // root
                               K::Node,     K::Axis, K::Split, K::Node, K::Leaf, K::Node, K::Leaf,  // 1, 2, 3
                               K::Node,     K::Axis, K::Split, K::Node, K::Leaf, K::Node, K::Leaf};  // 4, 5, 6
  ASSERT_EQ(kinds(t), want);
  expect_box(t.events[0].box, xbox(0, 6), "scene box");
  expect_node(t, t.events[1], 0, kNoBuildNode, 0, {0, 1, 2, 3});
  expect_box(t.events[1].box, xbox(0, 6), "root");
  expect_box(t.events[1].centroids, box(Vec3(0.5f), Vec3(6.5f, 0.5f, 0.5f)), "root centroids");
  EXPECT_EQ(t.events[2].axis, 0);
  EXPECT_EQ(t.events[2].dir, Vec3(1, 0, 0));
  const BuildEvent& s0 = t.events[3];
  EXPECT_EQ(s0.axis, 0);
  EXPECT_EQ(s0.pos, 3.5f);
  EXPECT_EQ(s0.a, 2u);
  EXPECT_EQ(s0.b, 2u);
  EXPECT_EQ(s0.count, 0u);
  EXPECT_EQ(s0.values[0], 4.0f);  // leaf cost ci * 4
  // SAH cost of the median split: children [0, 3] and [4, 7] (area 14 each), parent area 30.
  EXPECT_FLOAT_EQ(s0.cost, 1.0f + (14.0f * 2 + 14.0f * 2) / 30.0f);

  expect_node(t, t.events[4], 1, 0, 1, {1, 3});
  EXPECT_EQ(t.events[6].pos, 1.5f);
  expect_node(t, t.events[7], 2, 1, 2, {1});
  expect_leaf(t, t.events[8], 2, LeafReason::FewPrims, {1});
  expect_node(t, t.events[9], 3, 1, 2, {3});
  expect_leaf(t, t.events[10], 3, LeafReason::FewPrims, {3});
  expect_node(t, t.events[11], 4, 0, 1, {0, 2});
  EXPECT_EQ(t.events[13].pos, 5.5f);
  expect_leaf(t, t.events[15], 5, LeafReason::FewPrims, {0});
  expect_leaf(t, t.events[17], 6, LeafReason::FewPrims, {2});
  EXPECT_TRUE(r.tree.event_ids.empty());  // the event ids are the tree's indices
}

// Recorded to depth 1: the nodes at depth 2 appear as unrecorded subtrees (count only), with
// no steps of their own; the tree is the same.
TEST(BuildTraceBvh, MedianDepthLimit) {
  const Scene scene = unit_triangles({{4, 0, 0}, {0, 0, 0}, {6, 0, 0}, {2, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::Median;
  o.leaf_size = 1;
  BuildRecorder recorder(1);
  const BuildTree tree = build_bvh_tree(scene, o, nullptr, &recorder);
  testing::expect_same_tree(build_bvh_tree(scene, o), tree);
  const BuildTrace& t = recorder.trace();
  const std::vector<K> want = {K::SceneBox,   K::Node, K::Axis, K::Split,      K::Node,
                               K::Axis,       K::Split, K::Unrecorded, K::Unrecorded, K::Node,
                               K::Axis,       K::Split, K::Unrecorded, K::Unrecorded};
  ASSERT_EQ(kinds(t), want);
  EXPECT_EQ(t.events[7].node, 2u);
  EXPECT_EQ(t.events[7].count, 1u);
  EXPECT_EQ(t.coverage(), "recorded to depth 1 of 2");
}

// Round robin: depth 0 splits on x, depth 1 on y (all centres share y: the order is by
// triangle index, and the plane lies on the common centre).
TEST(BuildTraceBvh, MedianRoundRobinAxes) {
  const Scene scene = unit_triangles({{4, 0, 0}, {0, 0, 0}, {6, 0, 0}, {2, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::Median;
  o.axis = MedianAxis::RoundRobin;
  o.leaf_size = 1;
  const Recorded r = record(scene, o);
  std::vector<std::pair<uint32_t, int>> axes;
  for (const BuildEvent& e : r.trace.events)
    if (e.kind == K::Axis) axes.push_back({e.node, e.axis});
  EXPECT_EQ(axes, (std::vector<std::pair<uint32_t, int>>{{0, 0}, {1, 1}, {4, 1}}));
  const BuildEvent& leaf2 = r.trace.events[8];
  expect_leaf(r.trace, leaf2, 2, LeafReason::FewPrims, {1});  // {1, 3} split by index on y
  EXPECT_EQ(r.trace.events[6].pos, 0.5f);
}

// ----------------------------------------------------------------------------
// SAH sweep
// ----------------------------------------------------------------------------

// Corners x = 10, 0, 11, 1 (triangles 0..3); 4 triangles fit one leaf (leaf cost 4).
// Sweep on x (order 1, 3, 0, 2; parent [0, 12], area 50):
//   i = 1: 6 and [1, 12] (46):  1 + (6 + 46 * 3) / 50 = 3.88
//   i = 2: [0, 2] and [10, 12] (10 each): 1 + 40 / 50 = 1.8   <- the minimum
//   i = 3: 3.88
// On y and z every centre is the same: order by index 0, 1, 2, 3: 4.12, 4.68, 4.12.
// The children (2 triangles, leaf cost 2) sweep to 1 + 12 / 10 = 2.2 >= 2: leaves, no gain.
TEST(BuildTraceBvh, SahSweepCandidatesAndSplit) {
  const Scene scene = unit_triangles({{10, 0, 0}, {0, 0, 0}, {11, 0, 0}, {1, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::Sah;
  const Recorded r = record(scene, o);
  const BuildTrace& t = r.trace;
  const std::vector<K> want = {K::SceneBox,   K::Node,       K::Candidates, K::Candidates, K::Candidates,
                               K::Axis,       K::Split,      K::Node,       K::Candidates, K::Candidates,
                               K::Candidates, K::Axis,       K::Leaf,       K::Node,       K::Candidates,
                               K::Candidates, K::Candidates, K::Axis,       K::Leaf};
  ASSERT_EQ(kinds(t), want);
  expect_node(t, t.events[1], 0, kNoBuildNode, 0, {0, 1, 2, 3});
  const float want_costs[3][3] = {{3.88f, 1.8f, 3.88f}, {4.12f, 4.68f, 4.12f}, {4.12f, 4.68f, 4.12f}};
  float min_cost = kInf;
  for (int axis = 0; axis < 3; ++axis) {
    const BuildEvent& c = t.events[size_t(2 + axis)];
    EXPECT_EQ(c.node, 0u);
    EXPECT_EQ(c.axis, axis);
    ASSERT_EQ(c.list_count, 3u);
    for (uint32_t i = 0; i < 3; ++i) {
      const SplitCandidate& k = t.candidates_of(c)[i];
      EXPECT_FLOAT_EQ(k.cost, want_costs[axis][i]) << "axis " << axis << " position " << i + 1;
      EXPECT_EQ(k.left, i + 1);
      EXPECT_EQ(k.right, 3 - i);
      min_cost = std::min(min_cost, k.cost);
    }
  }
  const SplitCandidate* x = t.candidates_of(t.events[2]);
  EXPECT_EQ(x[0].pos, 1.0f);  // halfway between the centres 0.5 and 1.5
  EXPECT_EQ(x[1].pos, 6.0f);
  EXPECT_EQ(x[2].pos, 11.0f);
  EXPECT_EQ(t.candidates_of(t.events[3])[0].pos, 0.5f);  // y: all centres at 0.5
  EXPECT_EQ(t.events[5].axis, 0);
  const BuildEvent& s = t.events[6];
  EXPECT_EQ(s.axis, 0);
  EXPECT_EQ(s.cost, min_cost);  // the chosen split is the cheapest candidate
  EXPECT_EQ(s.cost, x[1].cost);
  EXPECT_EQ(s.pos, x[1].pos);
  EXPECT_EQ(s.values[0], 4.0f);
  EXPECT_EQ(s.a, 2u);
  EXPECT_EQ(s.b, 2u);

  expect_node(t, t.events[7], 1, 0, 1, {1, 3});
  EXPECT_FLOAT_EQ(t.candidates_of(t.events[8])[0].cost, 2.2f);
  expect_leaf(t, t.events[12], 1, LeafReason::NoGain, {1, 3});
  expect_node(t, t.events[13], 2, 0, 1, {0, 2});
  expect_leaf(t, t.events[18], 2, LeafReason::NoGain, {0, 2});
}

// PCA: the centres lie on the x axis, so the direction is x (axis 3 with dir (+-1, 0, 0)),
// and the sweep along it is the x sweep above.
TEST(BuildTraceBvh, PcaSweepAlongThePrincipalAxis) {
  const Scene scene = unit_triangles({{10, 0, 0}, {0, 0, 0}, {11, 0, 0}, {1, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::PcaSah;
  const Recorded r = record(scene, o);
  const BuildTrace& t = r.trace;
  ASSERT_GE(t.events.size(), 5u);
  const std::vector<K> head = {K::SceneBox, K::Node, K::Axis, K::Candidates, K::Split};
  const std::vector<K> all = kinds(t);
  ASSERT_EQ(std::vector<K>(all.begin(), all.begin() + 5), head);
  const BuildEvent& a = t.events[2];
  EXPECT_EQ(a.axis, 3);
  EXPECT_EQ(std::abs(a.dir.x), 1.0f);
  EXPECT_EQ(a.dir.y, 0.0f);
  EXPECT_EQ(a.dir.z, 0.0f);
  const BuildEvent& c = t.events[3];
  EXPECT_EQ(c.axis, 3);
  ASSERT_EQ(c.list_count, 3u);
  float min_cost = kInf;
  for (uint32_t i = 0; i < 3; ++i) min_cost = std::min(min_cost, t.candidates_of(c)[i].cost);
  EXPECT_FLOAT_EQ(t.candidates_of(c)[1].cost, 1.8f);
  EXPECT_EQ(std::abs(t.candidates_of(c)[1].pos), 6.0f);
  const BuildEvent& s = t.events[4];
  EXPECT_EQ(s.axis, 3);
  EXPECT_EQ(s.cost, min_cost);
  EXPECT_EQ(s.pos, t.candidates_of(c)[1].pos);
}

// ----------------------------------------------------------------------------
// Bottom-up (PLOC)
// ----------------------------------------------------------------------------

// Corners x = 10, 0, 11, 1 (triangles 0..3). Morton order along x: triangles 1, 3, 0, 2
// are clusters 0..3. Round 1: 0-1 (area 10) and 2-3 (area 10) are mutual nearest
// neighbours; round 2 merges them (area 50). Then the two pairs become leaves (2 * 10 <=
// 10 + 6 + 6); the root stays (4 * 50 > 50 + 20 + 20).
TEST(BuildTraceBvh, BottomUpMergeOrder) {
  const Scene scene = unit_triangles({{10, 0, 0}, {0, 0, 0}, {11, 0, 0}, {1, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::BottomUp;
  const Recorded r = record(scene, o);
  const BuildTrace& t = r.trace;
  const std::vector<K> want = {K::SceneBox, K::Node,  K::Leaf,  K::Node,  K::Leaf, K::Node, K::Leaf,
                               K::Node,     K::Leaf,  K::Merge, K::Merge, K::Merge, K::Leaf, K::Leaf};
  ASSERT_EQ(kinds(t), want);
  const uint32_t prim_of_cluster[4] = {1, 3, 0, 2};
  const float corner[4] = {0, 1, 10, 11};
  for (uint32_t c = 0; c < 4; ++c) {
    const BuildEvent& n = t.events[1 + 2 * c];
    expect_node(t, n, c, kNoBuildNode, 0, {prim_of_cluster[c]});
    expect_box(n.box, xbox(corner[c], corner[c]), "cluster");
    expect_leaf(t, t.events[2 + 2 * c], c, LeafReason::Cluster, {prim_of_cluster[c]});
  }
  expect_merge(t.events[9], 4, 0, 1, xbox(0, 1), 10.0f);
  expect_merge(t.events[10], 5, 2, 3, xbox(10, 11), 10.0f);
  expect_merge(t.events[11], 6, 4, 5, xbox(0, 11), 50.0f);
  expect_leaf(t, t.events[12], 4, LeafReason::NoGain, {1, 3});
  expect_leaf(t, t.events[13], 5, LeafReason::NoGain, {0, 2});
  EXPECT_EQ(r.tree.event_ids, (std::vector<uint32_t>{6, 4, 5}));
}

// ----------------------------------------------------------------------------
// Insertion (Goldsmith & Salmon)
// ----------------------------------------------------------------------------

// Corners x = 11, 1, 10, 0 (triangles 0..3). The seeded shuffle inserts 3, 1, 2, 0 (a step's
// box is the node's box after the insertion: grown when the triangle descends through it):
//   3 (x 0) is the root (id 0); 1 (x 1, id 1) meets the leaf: merge 2 = {0, 1}, area 10.
//   2 (x 10, id 3) at node 2: here = area [0, 11] = 46, grow = 46 - 10 = 36,
//     left (leaf x 0): 46 + 36 = 82, right (leaf x 1): area [1, 11] 42 + 36 = 78 -> here;
//     merge 4 = {2, 3}, area 46.
//   0 (x 11, id 5) at node 4 ([0, 11]): here = area [0, 12] = 50, grow = 50 - 46 = 4,
//     left (node 2, [0, 2], area 10): 50 - 10 + 4 = 44, right (leaf 3, [10, 11]): 10 + 4 = 14
//     -> right; leaf 3: merge 6 = {3, 5}, area 10, in 3's place.
// Final: nodes 2 and 6 become leaves (20 <= 22), the root 4 stays.
TEST(BuildTraceBvh, InsertionPathsCostsAndChoices) {
  const Scene scene = unit_triangles({{11, 0, 0}, {1, 0, 0}, {10, 0, 0}, {0, 0, 0}});
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::Insertion;
  const Recorded r = record(scene, o);
  const BuildTrace& t = r.trace;
  const std::vector<K> want = {K::SceneBox, K::Node,       K::Leaf,  K::Node,  K::Leaf, K::Merge,
                               K::Node,     K::Leaf,       K::InsertStep, K::Merge, K::Node, K::Leaf,
                               K::InsertStep, K::Merge,    K::Leaf,  K::Leaf};
  ASSERT_EQ(kinds(t), want);
  expect_node(t, t.events[1], 0, kNoBuildNode, 0, {3});
  expect_leaf(t, t.events[2], 0, LeafReason::Cluster, {3});
  expect_node(t, t.events[3], 1, kNoBuildNode, 0, {1});
  expect_merge(t.events[5], 2, 0, 1, xbox(0, 1), 10.0f);
  expect_node(t, t.events[6], 3, kNoBuildNode, 0, {2});

  const BuildEvent& s1 = t.events[8];
  EXPECT_EQ(s1.prim, 2u);
  EXPECT_EQ(s1.node, 2u);
  EXPECT_EQ(s1.depth, 0);
  expect_box(s1.box, xbox(0, 1), "node 2, not grown: the new parent bounds the triangle");
  EXPECT_EQ(s1.values[0], 46.0f);
  EXPECT_EQ(s1.values[1], 82.0f);
  EXPECT_EQ(s1.values[2], 78.0f);
  EXPECT_EQ(s1.a, 0u);  // sibling here
  expect_merge(t.events[9], 4, 2, 3, xbox(0, 10), 46.0f);

  expect_node(t, t.events[10], 5, kNoBuildNode, 0, {0});
  const BuildEvent& s2 = t.events[12];
  EXPECT_EQ(s2.prim, 0u);
  EXPECT_EQ(s2.node, 4u);
  EXPECT_EQ(s2.depth, 0);
  expect_box(s2.box, xbox(0, 11), "grown node 4");
  EXPECT_EQ(s2.values[0], 50.0f);
  EXPECT_EQ(s2.values[1], 44.0f);
  EXPECT_EQ(s2.values[2], 14.0f);
  EXPECT_EQ(s2.a, 2u);  // descend right
  expect_merge(t.events[13], 6, 3, 5, xbox(10, 11), 10.0f);
  expect_leaf(t, t.events[14], 2, LeafReason::NoGain, {3, 1});
  expect_leaf(t, t.events[15], 6, LeafReason::NoGain, {2, 0});
  EXPECT_EQ(r.tree.event_ids, (std::vector<uint32_t>{4, 2, 6}));
}

// ----------------------------------------------------------------------------
// The leaf rule at the depth limit (every top-down builder: leaf_verdict() in bvh_top_down.h)
// ----------------------------------------------------------------------------

/// A staircase of kMaxBvhDepth + 2 flat triangles, each twice the size of the one before
/// and beside it on x. With leaves priced per test of 64 (a leaf of up to 64 costs one test)
/// and cheap steps, the SAH sweep's best split peels the largest off the rest at every level
/// (ct + 1/4 + 1/2 of the parent's area; two off: ct + 1/16 + 3/4), and beats the leaf (1),
/// so the chain reaches the depth limit with 3 triangles left.
Scene doubling_staircase() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (uint32_t k = 0; k < uint32_t(kMaxBvhDepth) + 2; ++k) {
    const float s = std::ldexp(1.0f, int(k));
    p.insert(p.end(), {{s, 0, 0}, {2 * s, 0, 0}, {s, s, 0}});
    t.emplace_back(3 * k, 3 * k + 1, 3 * k + 2);
  }
  return Scene(std::move(p), std::move(t));
}

// A node at the depth limit that the leaf rule would have split is a MaxDepth leaf, small
// or not, for every builder (before, a small one was FewPrims for the sweep and PCA, NoGain
// for binned SAH and SBVH). At least the SAH sweep reaches the limit on this scene.
TEST(BuildTraceBvh, DepthLimitLeavesAreMaxDepthForEveryBuilder) {
  const Scene scene = doubling_staircase();
  bool sweep_reached = false;
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    SCOPED_TRACE(row.name);
    BvhBuildOptions o;
    o.builder = row.kind;
    o.prims_per_test = 64;
    o.ct = 0.01f;
    const Recorded r = record(scene, o);
    for (const BuildEvent& e : r.trace.events) {
      if (e.kind != K::Leaf || e.depth < kMaxBvhDepth - 1 || e.count < 2) continue;
      EXPECT_NE(e.reason, LeafReason::FewPrims) << "leaf " << e.node << " of " << e.count;
      if (e.reason == LeafReason::MaxDepth && e.count <= size_t(o.leaf_size) && row.kind == BvhBuilderKind::Sah)
        sweep_reached = true;
    }
  }
  EXPECT_TRUE(sweep_reached) << "the sweep never made a small leaf at the depth limit";
}

}  // namespace
}  // namespace accel
