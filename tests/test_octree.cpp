// Tests for core/octree: every option against the reference (shared suite), hand-checked
// traversal traces on tiny scenes, the build's stops and limits, and parameter validation.
// Index: [SECTION] Helpers, Hand-checked traces, Robustness, Build stops and limits, Parameters,
// Parallel build.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <functional>

#include "batch.h"
#include "structures/octree.h"
#include "random.h"
#include "registry.h"
#include "structure_suite.h"
#include "test_support.h"

namespace accel {
namespace testing {

// Every choice value at least once, plus the extremes of max_prims and max_depth.
INSTANTIATE_TEST_SUITE_P(
    Octree, StructureVsReference,
    ::testing::Values(SuiteCase{"octree", {}},                                     // exact, sorted, 8, 16
                      SuiteCase{"octree", {"order=fixed"}},                        // the lecture's 0..7 order
                      SuiteCase{"octree", {"insert=bbox"}},                        // the lecture's bbox insertion
                      SuiteCase{"octree", {"insert=bbox", "order=fixed"}},
                      SuiteCase{"octree", {"max_prims=1"}},                        // deepest trees
                      SuiteCase{"octree", {"max_prims=1", "insert=bbox", "max_depth=24"}},
                      SuiteCase{"octree", {"max_depth=4", "order=fixed"}},         // shallow, big leaves
                      SuiteCase{"octree", {"max_depth=40"}},                       // the deepest allowed
                      SuiteCase{"octree", {"max_prims=64"}}),                      // few, big leaves
    suite_case_name);
// max_depth = 0 and max_prims = 4096 make the octree a brute force, too slow for 100k rays
// per scene: OctreeParams.ExtremesBuildAndAnswer checks them on a small scene.

}  // namespace testing

namespace {

using testing::make_ray;
using testing::visited;
using testing::trace_tokens;

// [SECTION] Helpers

Scene make_scene(std::vector<std::array<Vec3, 3>> tris) {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (const auto& tri : tris) {
    const uint32_t i = uint32_t(p.size());
    p.insert(p.end(), tri.begin(), tri.end());
    t.emplace_back(i, i + 1, i + 2);
  }
  return Scene(std::move(p), std::move(t), "hand");
}

std::unique_ptr<Structure> build(const Scene& scene, const std::vector<std::string>& params) {
  auto built = build_structure("octree", scene, params);
  EXPECT_TRUE(built) << built.error().message;
  return built ? std::move(built.value()) : nullptr;
}

// [SECTION] Hand-checked traces
//
// Scene "octants": the root is the unit cube (T0 touches (0,0,0), T1 touches (1,1,1)), split
// once at 0.5 (max_prims = 1 and ct = 0, the stop by references alone; 5 triangles).
// Children are ids 1 + octant, octant bits x = 1, y = 2, z = 4 (set = upper half):
//   id 1 = octant 0 (x lo y lo z lo): T0 in the plane x = 0
//   id 2 = octant 1 (x hi y lo z lo): T2 in x = 0.75, y in [0.05, 0.45], z in [0.3, 0.45]
//   id 3 = octant 2 (x lo y hi z lo): T3 in x = 0.25, y in [0.55, 0.95], z in [0.3, 0.45]
//   id 4 = octant 3 (x hi y hi z lo): T4 in x = 0.75, y in [0.55, 0.95], z in [0.3, 0.45]
//   ids 5, 6, 7 = octants 4, 5, 6: empty leaves (never pushed, no event)
//   id 8 = octant 7 (x hi y hi z hi): T1 in the plane x = 1
// T2..T4 are right triangles with the right angle at (y lo, z = 0.3): a point is inside when
// z - 0.3 <= 0.375 * (y_max - y).
Scene octants_scene() {
  return make_scene({
      {Vec3(0, 0, 0), Vec3(0, 0.4f, 0), Vec3(0, 0, 0.4f)},                  // T0
      {Vec3(1, 1, 1), Vec3(1, 0.6f, 1), Vec3(1, 1, 0.6f)},                  // T1
      {Vec3(0.75f, 0.05f, 0.3f), Vec3(0.75f, 0.45f, 0.3f), Vec3(0.75f, 0.05f, 0.45f)},  // T2
      {Vec3(0.25f, 0.55f, 0.3f), Vec3(0.25f, 0.95f, 0.3f), Vec3(0.25f, 0.55f, 0.45f)},  // T3
      {Vec3(0.75f, 0.55f, 0.3f), Vec3(0.75f, 0.95f, 0.3f), Vec3(0.75f, 0.55f, 0.45f)},  // T4
  });
}

TEST(OctreeTrace, OctantsSceneHasTheExpectedLayout) {
  const Scene scene = octants_scene();
  auto s = build(scene, {"max_prims=1", "ct=0"});
  ASSERT_TRUE(s);
  const auto& octree = static_cast<const Octree&>(*s);
  EXPECT_EQ(octree.data().root_box.min, Vec3(0.0f));
  EXPECT_EQ(octree.data().root_box.max, Vec3(1.0f));
  ASSERT_EQ(octree.data().nodes.size(), 9u);
  EXPECT_FALSE(s->node_view(0).leaf);
  const std::vector<std::vector<uint32_t>> prims = {{0}, {2}, {3}, {4}, {}, {}, {}, {1}};
  for (unsigned octant = 0; octant < 8; ++octant) {
    const NodeView v = s->node_view(1 + octant);
    EXPECT_TRUE(v.leaf);
    EXPECT_EQ(v.depth, 1);
    EXPECT_EQ(s->node_prims(1 + octant), prims[octant]) << "octant " << octant;
    EXPECT_EQ(v.box.min, Vec3(octant & 1 ? 0.5f : 0.0f, octant & 2 ? 0.5f : 0.0f, octant & 4 ? 0.5f : 0.0f));
    EXPECT_EQ(v.box.max, v.box.min + Vec3(0.5f));
  }
  const BuildStats st = s->build_stats();
  EXPECT_EQ(st.nodes, 9u);
  EXPECT_EQ(st.leaves, 8u);
  EXPECT_EQ(st.empty_leaves, 3u);
  EXPECT_EQ(st.max_depth, 1);
  EXPECT_EQ(st.prim_references, 5u);
}

// The no-gain stop weighs the visits a split adds: the octants scene's root (5 triangles,
// each in one child: 5 references) splits while 3 ct + 5 / 4 < 5, i.e. for ct = 0 and 1,
// and is a leaf (no gain) for ct = 2, the default.
TEST(OctreeTrace, CtStopsASplitThatSavesLessThanItsVisits) {
  const Scene scene = octants_scene();
  for (const char* ct : {"ct=0", "ct=1", "ct=2"}) {
    SCOPED_TRACE(ct);
    auto s = build(scene, {"max_prims=1", ct});
    ASSERT_TRUE(s);
    const OctreeData& data = static_cast<const Octree&>(*s).data();
    const bool splits = std::string(ct) != "ct=2";
    EXPECT_EQ(data.nodes.size(), splits ? 9u : 1u);
    EXPECT_EQ(data.reasons.no_gain, splits ? 0u : 1u);
  }
}

// Ray R1 from (1, 0.1, 0.25) along (-1, 1, 0), starting on the root's face x = 1, below
// every triangle (z = 0.25 < 0.3), so nothing is hit and every child it passes is visited.
// It passes octant 1 (t in [0, 0.4]), then octant 3 (y > 0.5 from t = 0.4), then octant 2
// (x < 0.5 from t = 0.5); it misses octant 0 (x < 0.5 only once y > 0.5) and octant 7 (z).
/// Ray R1 through the octants scene's octree (max_prims=1) with child `order`: no hit.
TraceRecorder trace_r1(const std::string& order) {
  const Scene scene = octants_scene();
  auto s = build(scene, {"max_prims=1", "ct=0", "order=" + order});
  TraceRecorder rec;
  if (!s) return rec;  // build() has reported the failure
  EXPECT_FALSE(s->intersect_traced(make_ray({1.0f, 0.1f, 0.25f}, {-1, 1, 0}), rec).valid());
  return rec;
}

TEST(OctreeTrace, FixedOrderVisitsOctantsZeroToSeven) {
  const TraceRecorder rec = trace_r1("fixed");
  // The lecture's order: children tested 0..7 (ids 1..8), the hit ones pushed in reverse
  // so id 2 (octant 1) pops first, then id 3 (octant 2), then id 4 (octant 3): octant 2 is
  // visited before octant 3 although the ray reaches it later.
  const std::vector<std::string> expected = {
      "push 0", "pop 0", "visit 0",
      "cull 1 missed", "cull 8 missed", "push 4", "push 3", "push 2",
      "pop 2", "visit 2", "test 2 miss",
      "pop 3", "visit 3", "test 3 miss",
      "pop 4", "visit 4", "test 4 miss",
      "done -1"};
  EXPECT_EQ(trace_tokens(rec), expected);
  EXPECT_EQ(visited(rec), (std::vector<NodeId>{0, 2, 3, 4}));
}

TEST(OctreeTrace, SortedOrderVisitsOctantsFrontToBack) {
  const TraceRecorder rec = trace_r1("sorted");
  // The ray travels down x only: mask = 1, octants tested in the order i ^ 1 =
  // 1, 0, 3, 2, 5, 4, 7, 6 (ids 2, 1, 4, 3, 6, 5, 8, 7): the passed ones in the ray's order
  // 1, 3, 2 = ids 2, 4, 3, whose entry distances 0, 0.4, 0.5 increase.
  const std::vector<std::string> expected = {
      "push 0", "pop 0", "visit 0",
      "cull 1 missed", "cull 8 missed", "push 3", "push 4", "push 2",
      "pop 2", "visit 2", "test 2 miss",
      "pop 4", "visit 4", "test 4 miss",
      "pop 3", "visit 3", "test 3 miss",
      "done -1"};
  EXPECT_EQ(trace_tokens(rec), expected);
  std::vector<float> entries;
  for (const TraceEvent& e : rec.events())
    if (e.kind == TraceEventKind::Visit && e.node != 0) entries.push_back(e.t0);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_FLOAT_EQ(entries[0], 0.0f);
  EXPECT_NEAR(entries[1], 0.4f, 1e-6f);
  EXPECT_NEAR(entries[2], 0.5f, 1e-6f);
}

// Ray R3 from (0.1, 1, 0.32) along (1, -1, 0), on the root's face y = 1: octant 2 for t in
// [0, 0.4] (hits T3 at t = 0.15, x = 0.25, y = 0.85), octant 3 for [0.4, 0.5] (misses T4),
// octant 1 for [0.5, 0.9] (would hit T2 at t = 0.65, x = 0.75, y = 0.35).
TEST(OctreeTrace, SortedSkipsChildrenBeyondTheClosestHit) {
  const Scene scene = octants_scene();
  auto s = build(scene, {"max_prims=1", "ct=0", "order=sorted"});
  ASSERT_TRUE(s);
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({0.1f, 1.0f, 0.32f}, {1, -1, 0}), rec);
  EXPECT_EQ(h.prim, 3);
  EXPECT_NEAR(h.t, 0.15f, 1e-6f);
  // mask = 2 (down y): octants 2, 3, 0, 1, 6, 7, 4, 5. After T3 at 0.15 in octant 2 (id 3),
  // octant 3 (id 4, entry 0.4) and octant 1 (id 2, entry 0.5) are popped and skipped.
  const std::vector<std::string> expected = {
      "push 0", "pop 0", "visit 0",
      "cull 1 missed", "cull 8 missed", "push 2", "push 4", "push 3",
      "pop 3", "visit 3", "test 3 hit", "closest 3",
      "pop 4", "cull 4 beyond",
      "pop 2", "cull 2 beyond",
      "done 3"};
  EXPECT_EQ(trace_tokens(rec), expected);
  for (const TraceEvent& e : rec.events()) {
    if (e.kind == TraceEventKind::Cull && e.reason == CullReason::BeyondClosestHit) {
      EXPECT_NEAR(e.t0, e.node == 4 ? 0.4f : 0.5f, 1e-6f);  // the skipped node's entry
      EXPECT_GT(e.t0, h.t);
    }
  }
  EXPECT_EQ(visited(rec), (std::vector<NodeId>{0, 3}));
}

TEST(OctreeTrace, FixedOrderFindsTheFarHitFirstThenTheCloserOne) {
  const Scene scene = octants_scene();
  auto s = build(scene, {"max_prims=1", "ct=0", "order=fixed"});
  ASSERT_TRUE(s);
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({0.1f, 1.0f, 0.32f}, {1, -1, 0}), rec);
  EXPECT_EQ(h.prim, 3);
  // Octant 1 (id 2) comes first in the lecture's order although the ray reaches it last:
  // T2 at 0.65 is found first; octant 2 (id 3, entry 0 < 0.65) still has to be visited and
  // gives T3 at 0.15; only octant 3 (id 4, entry 0.4 > 0.15) is skipped.
  const std::vector<std::string> expected = {
      "push 0", "pop 0", "visit 0",
      "cull 1 missed", "cull 8 missed", "push 4", "push 3", "push 2",
      "pop 2", "visit 2", "test 2 hit", "closest 2",
      "pop 3", "visit 3", "test 3 hit", "closest 3",
      "pop 4", "cull 4 beyond",
      "done 3"};
  EXPECT_EQ(trace_tokens(rec), expected);
}

// Scene "straddle" (max_prims = 2, ct = 0; same corner triangles TA, TB as above, so the
// root is the unit cube again): S reaches from x = 0.1 (octant 0) to x = 0.95 (octant 1) and is hit by
// the ray below at x = 0.78, in octant 1; C in the plane x = 0.6, also in octant 1, is
// closer. Leaves: id 1 = octant 0 {TA, S}, id 2 = octant 1 {S, C}, id 8 = octant 7 {TB}.
TEST(OctreeTrace, StraddlingTriangleHitInTheFarChildDoesNotEndTheSearch) {
  const Scene scene = make_scene({
      {Vec3(0, 0, 0), Vec3(0, 0.4f, 0), Vec3(0, 0, 0.4f)},                      // 0: TA
      {Vec3(1, 1, 1), Vec3(1, 0.6f, 1), Vec3(1, 1, 0.6f)},                      // 1: TB
      {Vec3(0.1f, 0.0f, 0.45f), Vec3(0.1f, 0.45f, 0.45f), Vec3(0.95f, 0.25f, 0.2f)},  // 2: S
      {Vec3(0.6f, 0.05f, 0.05f), Vec3(0.6f, 0.48f, 0.05f), Vec3(0.6f, 0.05f, 0.48f)},  // 3: C
  });
  for (const char* order : {"order=sorted", "order=fixed"}) {
    SCOPED_TRACE(order);
    auto s = build(scene, {"max_prims=2", "ct=0", order});
    ASSERT_TRUE(s);
    EXPECT_EQ(s->node_prims(1), (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(s->node_prims(2), (std::vector<uint32_t>{2, 3}));
    TraceRecorder rec;
    const Hit h = s->intersect_traced(make_ray({-1.0f, 0.25f, 0.25f}, {1, 0, 0}), rec);
    EXPECT_EQ(h.prim, 3);
    EXPECT_NEAR(h.t, 1.6f, 1e-6f);
    // The ray goes up every axis, so both orders test octants 0..7. Octant 0 (id 1, entry 1)
    // gives S at 1.78, beyond its exit 1.5; octant 1 (entry 1.5 < 1.78) is still visited
    // and gives the closer C at 1.6.
    const std::vector<std::string> expected = {
        "push 0", "pop 0", "visit 0",
        "cull 8 missed", "push 2", "push 1",
        "pop 1", "visit 1", "test 0 miss", "test 2 hit", "closest 2",
        "pop 2", "visit 2", "test 2 hit", "test 3 hit", "closest 3",
        "done 3"};
    // Re-testing S in octant 1 with tmax = its own t may report hit or miss (the kernel
    // decides at tmax in double): compare that one step by its triangle only.
    std::vector<std::string> got = trace_tokens(rec);
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(got[13].substr(0, 7), "test 2 ");
    got[13] = expected[13];
    EXPECT_EQ(got, expected);
    for (const TraceEvent& e : rec.events()) {
      if (e.kind == TraceEventKind::NewClosest && e.prim == 2) {
        EXPECT_NEAR(e.t0, 1.78f, 1e-5f);
      }
    }
  }
}

TEST(OctreeTrace, RecordingNeverChangesTheAnswer) {
  const Scene scene = make_procedural_scene("soup").value();
  for (const char* order : {"order=sorted", "order=fixed"}) {
    auto s = build(scene, {order});
    ASSERT_TRUE(s);
    for (const Ray& r : random_rays(scene.bounds(), 300, 5)) {
      TraceRecorder rec;
      QueryStats q;
      const Hit a = s->intersect(r), b = s->intersect_traced(r, rec), c = s->intersect(r, &q);
      EXPECT_EQ(a.prim, b.prim);
      EXPECT_EQ(a.t, b.t);
      EXPECT_EQ(a.prim, c.prim);
      EXPECT_EQ(rec.stats().nodes_visited, q.nodes_visited);
      EXPECT_EQ(rec.stats().prims_tested, q.prims_tested);
      EXPECT_EQ(rec.stats().max_stack, q.max_stack);
    }
  }
}

// [SECTION] Robustness

/// Every hit correct by docs/hits.md's rule (testing::hit_is_correct against the double
/// reference). Not "same t as brute force": the watertight kernel defers to double near
/// tmax, and tmax (the closest hit so far) differs with the order triangles are tested in.
void expect_correct(const Scene& scene, const std::vector<std::string>& params, const std::vector<Ray>& rays) {
  auto octree = build(scene, params);
  ASSERT_TRUE(octree);
  size_t wrong = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    std::string why;
    if (!testing::hit_is_correct(scene, rays[i], octree->intersect(rays[i]), testing::reference_closest(scene, rays[i]),
                                 &why) &&
        ++wrong <= 5)
      ADD_FAILURE() << "ray " << i << " org (" << rays[i].org.x << ", " << rays[i].org.y << ", " << rays[i].org.z
                    << ") dir (" << rays[i].dir.x << ", " << rays[i].dir.y << ", " << rays[i].dir.z << "): " << why;
  }
  EXPECT_EQ(wrong, 0u);
}

/// Random triangles in the unit cube plus triangles lying in the split planes x, y, z = 0.5
/// and 0.25 (level-1 and level-2 planes), and axis-parallel rays starting on or travelling
/// inside those planes, through the corners, edges and faces of cells.
TEST(OctreeRobustness, RaysAndTrianglesOnSplitPlanes) {
  std::vector<std::array<Vec3, 3>> tris;
  Rng rng(11);
  for (int i = 0; i < 300; ++i) {
    const Vec3 c(rng.uniform(), rng.uniform(), rng.uniform());
    tris.push_back({c, c + Vec3(rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f)),
                    c + Vec3(rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f))});
  }
  for (float plane : {0.25f, 0.5f, 0.75f}) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < 20; ++k) {
        std::array<Vec3, 3> t;
        for (Vec3& v : t) {
          v = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
          v[axis] = plane;
        }
        tris.push_back(t);
      }
    }
  }
  tris.push_back({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 1)});  // pins the root to the unit cube
  tris.push_back({Vec3(1, 1, 1), Vec3(1, 0, 1), Vec3(0, 1, 0)});
  const Scene scene = make_scene(tris);

  std::vector<Ray> rays;
  const float coords[] = {0.0f, 0.125f, 0.25f, 0.3f, 0.5f, 0.625f, 0.75f, 1.0f};
  for (int axis = 0; axis < 3; ++axis) {
    for (float a : coords) {
      for (float b : coords) {
        for (float sign : {1.0f, -1.0f}) {
          Ray r;  // axis-parallel, starting outside
          r.org[axis] = sign > 0 ? -1.0f : 2.0f;
          r.org[(axis + 1) % 3] = a;
          r.org[(axis + 2) % 3] = b;
          r.dir = Vec3(0.0f);
          r.dir[axis] = sign;
          rays.push_back(r);
          r.org[axis] = 0.5f;  // starting on a split plane, inside the scene
          rays.push_back(r);
          Ray d = r;  // diagonal within the plane (axis+1) = a: travels inside a split plane
          d.dir[(axis + 2) % 3] = sign * 0.5f;
          rays.push_back(d);
          d.dir[(axis + 1) % 3] = -0.0f;  // negative zero component
          rays.push_back(d);
        }
      }
    }
  }
  for (const Ray& r : random_rays(scene.bounds(), 2000, 3)) rays.push_back(r);
  for (const auto& params : std::vector<std::vector<std::string>>{
           {}, {"max_prims=1"}, {"insert=bbox", "order=fixed"}, {"max_prims=1", "max_depth=40"}}) {
    SCOPED_TRACE(params.empty() ? "defaults" : params[0]);
    expect_correct(scene, params, rays);
  }
}

TEST(OctreeRobustness, FlatSceneGetsACubicRoot) {
  // All triangles in z = 0.5: a zero-thickness scene box. The root is still a cube, so
  // children have volume; rays parallel to the plane (z = 0.5) and through it work.
  std::vector<std::array<Vec3, 3>> tris;
  Rng rng(2);
  for (int i = 0; i < 500; ++i) {
    const Vec3 c(rng.uniform(), rng.uniform(), 0.5f);
    tris.push_back({c, c + Vec3(rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f), 0),
                    c + Vec3(rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f), 0)});
  }
  const Scene scene = make_scene(tris);
  auto s = build(scene, {});
  ASSERT_TRUE(s);
  const Aabb root = s->node_view(0).box;
  const Vec3 e = root.extent();
  EXPECT_FLOAT_EQ(e.x, e.z);
  EXPECT_FLOAT_EQ(e.y, e.z);
  EXPECT_GT(s->build_stats().nodes, 9u);
  std::vector<Ray> rays = random_rays(scene.bounds(), 3000, 8);
  for (int i = 0; i < 200; ++i) {
    rays.push_back(make_ray({rng.uniform(), rng.uniform(), 1.0f}, {0, 0, -1}));
    rays.push_back(make_ray({rng.uniform(), rng.uniform(), 0.5f}, {rng.uniform(-1, 1), rng.uniform(-1, 1), 0}));
  }
  expect_correct(scene, {}, rays);
  expect_correct(scene, {"max_prims=1", "max_depth=40"}, rays);
}

TEST(OctreeRobustness, OriginInsideAndTminTmaxInclusive) {
  const Scene scene = octants_scene();
  auto s = build(scene, {"max_prims=1"});
  ASSERT_TRUE(s);
  Ray r = make_ray({0.5f, 0.35f, 0.32f}, {1, 0, 0});  // origin on the centre plane x = 0.5
  Hit h = s->intersect(r);
  EXPECT_EQ(h.prim, 2);
  EXPECT_FLOAT_EQ(h.t, 0.25f);
  r.tmax = 0.25f;  // hit exactly at tmax counts
  EXPECT_EQ(s->intersect(r).prim, 2);
  r.tmin = 0.25f;  // and exactly at tmin
  EXPECT_EQ(s->intersect(r).prim, 2);
  r.tmax = 0.2499f;
  r.tmin = 0.0f;
  EXPECT_FALSE(s->intersect(r).valid());
}

// [SECTION] Build stops and limits

TEST(OctreeBuild, ManyTrianglesSharingAVertexDoNotExplode) {
  // A fan of 64 triangles around a vertex: no split can ever separate them near the vertex
  // (nor two neighbours along their shared edge). max_prims = 1 and max_depth = 40 still
  // give a small tree. The last triangle moves the root so the apex is on no split plane.
  std::vector<std::array<Vec3, 3>> tris = {{Vec3(2.1f, 1.7f, 1.9f), Vec3(2.2f, 1.7f, 1.9f), Vec3(2.1f, 1.8f, 1.9f)}};
  const Vec3 apex(0.3f, 0.3f, 0.3f);
  for (int i = 0; i < 64; ++i) {
    const float a0 = 6.2831853f * float(i) / 64, a1 = 6.2831853f * float(i + 1) / 64;
    tris.push_back({apex, apex + Vec3(std::cos(a0), std::sin(a0), 0.3f), apex + Vec3(std::cos(a1), std::sin(a1), 0.3f)});
  }
  const Scene scene = make_scene(tris);
  auto s = build(scene, {"max_prims=1", "max_depth=40"});
  ASSERT_TRUE(s);
  const BuildStats st = s->build_stats();
  EXPECT_LT(st.nodes, 20000u);
  EXPECT_LT(st.max_depth, 40);
  const auto& reasons = static_cast<const Octree&>(*s).data().reasons;
  EXPECT_GT(reasons.inseparable + reasons.no_gain, 0u);
  expect_correct(scene, {"max_prims=1", "max_depth=40"}, random_rays(scene.bounds(), 2000, 4));
  // Identical triangles: every child gets all of them, so the root stays a leaf.
  const Scene same = make_scene(std::vector<std::array<Vec3, 3>>(100, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 1)}));
  auto t = build(same, {"max_prims=1", "max_depth=40"});
  ASSERT_TRUE(t);
  EXPECT_EQ(t->build_stats().nodes, 1u);
}

TEST(OctreeBuild, NodeBudgetGivesAClearError) {
  // The real limits (2^32 nodes and references, the memory budget first) take long to reach; the same code path
  // with small limits: 10k random triangles at max_prims = 1 need far more than 10000 nodes.
  const Scene scene = make_procedural_scene("soup").value();
  OctreeBuildOptions options;
  options.max_prims = 1;
  options.max_depth = 40;
  options.node_limit = 10000;
  auto built = build_octree(scene, options);
  ASSERT_FALSE(built);
  EXPECT_NE(built.error().message.find("octree parameter 'max_depth' = 40 (with max_prims = 1)"), std::string::npos)
      << built.error().message;
  EXPECT_NE(built.error().message.find("more than 10000 nodes"), std::string::npos) << built.error().message;
  EXPECT_NE(built.error().message.find("lower max_depth or raise max_prims"), std::string::npos);
  options.node_limit = size_t(1) << 25;
  options.reference_limit = 5000;
  auto refs = build_octree(scene, options);
  ASSERT_FALSE(refs);
  EXPECT_NE(refs.error().message.find("more than 5000 triangle references"), std::string::npos)
      << refs.error().message;
  // Within the real limits the same settings build.
  options.reference_limit = size_t(1) << 27;
  EXPECT_TRUE(build_octree(scene, options));
}

TEST(OctreeBuild, ExactInsertionStoresFewerReferencesThanBbox) {
  const Scene scene = make_procedural_scene("sphere").value();
  auto exact = build(scene, {"insert=exact"});
  auto bbox = build(scene, {"insert=bbox"});
  ASSERT_TRUE(exact && bbox);
  EXPECT_LT(exact->build_stats().prim_references, bbox->build_stats().prim_references);
}

TEST(OctreeBuild, ForEachNodeMatchesNodeView) {
  const Scene scene = make_procedural_scene("cornell").value();
  auto s = build(scene, {"max_prims=2"});
  ASSERT_TRUE(s);
  size_t count = 0, leaves = 0, refs = 0;
  const Aabb root = s->node_view(0).box;
  s->for_each_node([&](const NodeView& v) {
    EXPECT_EQ(v.id, NodeId(count));
    ++count;
    const NodeView w = s->node_view(v.id);
    EXPECT_EQ(v.box.min, w.box.min);
    EXPECT_EQ(v.box.max, w.box.max);
    EXPECT_EQ(v.depth, w.depth);
    EXPECT_EQ(v.leaf, w.leaf);
    EXPECT_EQ(v.prim_count, w.prim_count);
    EXPECT_TRUE(root.contains(v.box));
    EXPECT_EQ(s->node_prims(v.id).size(), v.leaf ? v.prim_count : 0u);
    leaves += v.leaf;
    refs += v.prim_count;
    for (uint32_t prim : s->node_prims(v.id)) {  // every stored triangle overlaps its leaf
      EXPECT_TRUE(triangle_overlaps_box(scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), v.box));
    }
  });
  const BuildStats st = s->build_stats();
  EXPECT_EQ(count, st.nodes);
  EXPECT_EQ(leaves, st.leaves);
  EXPECT_EQ(refs, st.prim_references);
  EXPECT_EQ(s->node_view(NodeId(count)).id, kNoNode);  // out of range
  EXPECT_TRUE(s->node_prims(NodeId(count)).empty());
}

TEST(OctreeBuild, TriangleBoxOverlapIsExactOnTouchingCases) {
  const Aabb box{Vec3(0), Vec3(1)};
  // Touching a face, an edge and a corner from outside: overlap (closed box).
  EXPECT_TRUE(triangle_overlaps_box(Vec3(1, 0.2f, 0.2f), Vec3(2, 0.2f, 0.2f), Vec3(2, 0.8f, 0.8f), box));
  EXPECT_TRUE(triangle_overlaps_box(Vec3(1, 1, 0.5f), Vec3(2, 1, 0.5f), Vec3(1, 2, 0.5f), box));
  EXPECT_TRUE(triangle_overlaps_box(Vec3(1, 1, 1), Vec3(2, 1, 1), Vec3(1, 2, 1), box));
  // Its bounding box overlaps the box, the triangle does not (separated by an edge axis):
  // the corner (1,1,1) lies below the plane x + y = 2.1 the triangle's hypotenuse spans.
  EXPECT_FALSE(triangle_overlaps_box(Vec3(2.1f, 0, 0.5f), Vec3(0, 2.1f, 0.5f), Vec3(2.1f, 2.1f, 0.5f), box));
  // Separated by the triangle's plane x + y + z = 3.1 (bounding boxes overlap).
  EXPECT_FALSE(triangle_overlaps_box(Vec3(3.1f, 0, 0), Vec3(0, 3.1f, 0), Vec3(0, 0, 3.1f), box));
  EXPECT_TRUE(triangle_overlaps_box(Vec3(3, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 3), box));  // touches (1,1,1)
  // A big triangle through the middle, all vertices outside.
  EXPECT_TRUE(triangle_overlaps_box(Vec3(-5, -5, 0.5f), Vec3(5, -5, 0.5f), Vec3(0, 10, 0.5f), box));
}

// [SECTION] Parameters

TEST(OctreeParams, OutOfRangeValuesAreRejectedNamingTheParameter) {
  const Scene scene = octants_scene();
  auto expect_error = [&](const std::string& kv, const std::string& text) {
    auto built = build_structure("octree", scene, {kv});
    ASSERT_FALSE(built) << kv;
    EXPECT_NE(built.error().message.find(text), std::string::npos) << built.error().message;
  };
  expect_error("max_prims=0", "octree parameter 'max_prims' = '0' is invalid: expected an integer in [1, 4096]");
  expect_error("max_prims=4097", "an integer in [1, 4096]");
  expect_error("max_depth=-1", "octree parameter 'max_depth' = '-1' is invalid: expected an integer in [0, 40]");
  expect_error("max_depth=41", "an integer in [0, 40]");
  expect_error("insert=clip", "octree parameter 'insert' = 'clip' is invalid: expected one of: bbox, exact");
  expect_error("order=random", "expected one of: sorted, fixed");
}

TEST(OctreeParams, ExtremesBuildAndAnswer) {
  const Scene scene = make_procedural_scene("cornell").value();
  for (const auto& params : std::vector<std::vector<std::string>>{
           {"max_depth=0"}, {"max_depth=40", "max_prims=1"}, {"max_prims=4096"}, {"max_prims=1", "insert=bbox"}}) {
    SCOPED_TRACE(params[0]);
    expect_correct(scene, params, random_rays(scene.bounds(), 2000, 6));
  }
  auto leaf = build(scene, {"max_depth=0"});
  ASSERT_TRUE(leaf);
  EXPECT_EQ(leaf->build_stats().nodes, 1u);
  EXPECT_EQ(leaf->build_stats().prim_references, scene.valid_prims().size());
}


// [SECTION] Parallel build

/// build_octree() on `threads` TBB threads.
Result<OctreeData> build_on_threads(const Scene& scene, const OctreeBuildOptions& options, int threads) {
  tbb::task_arena arena(threads);
  return arena.execute([&] { return build_octree(scene, options); });
}

void expect_identical(const OctreeData& a, const OctreeData& b, const std::string& what) {
  EXPECT_EQ(a.root_box.min, b.root_box.min) << what;
  EXPECT_EQ(a.root_box.max, b.root_box.max) << what;
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << what;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes[i].first, b.nodes[i].first) << what << ": node " << i;
    ASSERT_EQ(a.nodes[i].count, b.nodes[i].count) << what << ": node " << i;
  }
  EXPECT_EQ(a.prim_ids, b.prim_ids) << what;
  EXPECT_EQ(a.parents, b.parents) << what;
  EXPECT_EQ(a.depths, b.depths) << what;
  EXPECT_EQ(a.reasons.few_prims, b.reasons.few_prims) << what;
  EXPECT_EQ(a.reasons.max_depth, b.reasons.max_depth) << what;
  EXPECT_EQ(a.reasons.no_gain, b.reasons.no_gain) << what;
  EXPECT_EQ(a.reasons.inseparable, b.reasons.inseparable) << what;
  EXPECT_EQ(a.reasons.tiny_box, b.reasons.tiny_box) << what;
}

/// triangle_overlaps_box() as first written (generic index loops), for the reference build:
/// the written-out version must answer the same.
bool generic_overlaps_box(const Vec3& a, const Vec3& b, const Vec3& c, const Aabb& box) {
  const DVec3 centre = 0.5 * (DVec3(box.min) + DVec3(box.max));
  const DVec3 v0 = DVec3(a) - centre, v1 = DVec3(b) - centre, v2 = DVec3(c) - centre;
  const DVec3 reach = glm::max(glm::abs(v0), glm::max(glm::abs(v1), glm::abs(v2)));
  const double far = std::max(reach.x, std::max(reach.y, reach.z));
  const DVec3 h = 0.5 * (DVec3(box.max) - DVec3(box.min)) * (1.0 + 0x1p-20) + DVec3(far * 0x1p-40);
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = std::min(v0[axis], std::min(v1[axis], v2[axis]));
    const double hi = std::max(v0[axis], std::max(v1[axis], v2[axis]));
    if (lo > h[axis] || hi < -h[axis]) return false;
  }
  const DVec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
  const DVec3* verts[3] = {&v0, &v1, &v2};
  for (const DVec3& f : edges) {
    for (int axis = 0; axis < 3; ++axis) {
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      double lo = INFINITY, hi = -INFINITY;
      for (const DVec3* v : verts) {
        const double p = -f[j] * (*v)[i] + f[i] * (*v)[j];
        lo = std::min(lo, p);
        hi = std::max(hi, p);
      }
      const double r = h[i] * std::abs(f[j]) + h[j] * std::abs(f[i]);
      if (lo > r || hi < -r) return false;
    }
  }
  const DVec3 n = glm::cross(v1 - v0, v2 - v0);
  const double d = glm::dot(n, v0);
  const double r = h.x * std::abs(n.x) + h.y * std::abs(n.y) + h.z * std::abs(n.z);
  return std::abs(d) <= r;
}

/// The build as it was before it went parallel (one recursion, the generic overlap test for
/// every candidate child): the oracle for the parallel builder's numbering and for child_mask()'s
/// shortcuts. Limits and progress left out.
class ReferenceOctreeBuilder {
 public:
  ReferenceOctreeBuilder(const Scene& scene, const OctreeBuildOptions& options) : scene_(scene), options_(options) {}
  OctreeData run() {
    Aabb bounds;
    for (uint32_t prim : scene_.valid_prims()) bounds.extend(scene_.triangle_bounds(prim));
    data_.root_box = octree_root_box(bounds);
    add(kNoNode, 0);
    node(0, data_.root_box, 0, scene_.valid_prims());
    return std::move(data_);
  }

 private:
  void add(uint32_t parent, int depth) {
    data_.nodes.push_back({});
    data_.parents.push_back(parent);
    data_.depths.push_back(uint8_t(depth));
  }
  void leaf(uint32_t id, const std::vector<uint32_t>& prims, size_t* reason) {
    data_.nodes[id] = OctreeNode{uint32_t(data_.prim_ids.size()), uint32_t(prims.size())};
    data_.prim_ids.insert(data_.prim_ids.end(), prims.begin(), prims.end());
    ++*reason;
  }
  void node(uint32_t id, const Aabb& box, int depth, const std::vector<uint32_t>& prims) {
    OctreeLeafReasons& why = data_.reasons;
    if (prims.size() <= size_t(options_.max_prims)) return leaf(id, prims, &why.few_prims);
    if (depth >= options_.max_depth) return leaf(id, prims, &why.max_depth);
    const Vec3 mid = 0.5f * box.min + 0.5f * box.max;
    for (int axis = 0; axis < 3; ++axis)
      if (mid[axis] <= box.min[axis] || mid[axis] >= box.max[axis]) return leaf(id, prims, &why.tiny_box);
    std::array<std::vector<uint32_t>, 8> children;
    for (uint32_t prim : prims) {
      const Aabb& tb = scene_.triangle_bounds(prim);
      for (unsigned octant = 0; octant < 8; ++octant) {
        bool reaches = true;
        for (int axis = 0; axis < 3; ++axis)
          reaches &= (octant >> axis) & 1u ? tb.max[axis] >= mid[axis] : tb.min[axis] <= mid[axis];
        if (reaches && options_.insert == OctreeInsert::Exact)
          reaches = generic_overlaps_box(scene_.vertex(prim, 0), scene_.vertex(prim, 1), scene_.vertex(prim, 2),
                                         octree_child_box(box, octant));
        if (reaches) children[octant].push_back(prim);
      }
    }
    const size_t n = prims.size();
    size_t refs = 0;
    for (const auto& child : children) refs += child.size();
    if (3.0 * options_.ct + double(refs) / 4.0 >= double(n)) return leaf(id, prims, &why.no_gain);
    const uint32_t first = uint32_t(data_.nodes.size());
    for (int k = 0; k < 8; ++k) add(id, depth + 1);
    data_.nodes[id] = OctreeNode{first, OctreeNode::kInner};
    const bool poor = refs >= 2 * n;
    Aabb bounds;
    for (uint32_t prim : prims) bounds.extend(scene_.triangle_bounds(prim));
    for (unsigned octant = 0; octant < 8; ++octant) {
      const Aabb child_box = octree_child_box(box, octant);
      if (children[octant].size() == n && (poor || bounds.contains(child_box)))
        leaf(first + octant, children[octant], &why.inseparable);
      else
        node(first + octant, child_box, depth + 1, children[octant]);
    }
  }

  const Scene& scene_;
  const OctreeBuildOptions& options_;
  OctreeData data_;
};

/// Every build option, on scenes big enough for parallel children and parallel child masks
/// (the stadium's root holds 20k+ triangles).
std::vector<std::pair<std::string, OctreeBuildOptions>> parallel_cases() {
  std::vector<std::pair<std::string, OctreeBuildOptions>> cases;
  const auto add = [&](const std::string& name, const std::function<void(OctreeBuildOptions&)>& set) {
    OctreeBuildOptions o;
    set(o);
    cases.emplace_back(name, o);
  };
  add("defaults (exact, 8, 16)", [](OctreeBuildOptions&) {});
  add("insert=bbox", [](OctreeBuildOptions& o) { o.insert = OctreeInsert::Bbox; });
  add("max_prims=1 max_depth=24", [](OctreeBuildOptions& o) { o.max_prims = 1, o.max_depth = 24; });
  add("max_prims=1 insert=bbox", [](OctreeBuildOptions& o) { o.max_prims = 1, o.insert = OctreeInsert::Bbox; });
  add("max_prims=64 max_depth=5", [](OctreeBuildOptions& o) { o.max_prims = 64, o.max_depth = 5; });
  add("max_depth=1", [](OctreeBuildOptions& o) { o.max_depth = 1; });
  return cases;
}

TEST(OctreeParallel, OneAndFourThreadsBuildTheSameTree) {
  for (const char* name : {"stadium", "soup", "sphere"}) {
    const Scene scene = make_procedural_scene(name).value();
    for (const auto& [label, options] : parallel_cases()) {
      const std::string what = std::string(name) + " " + label;
      auto one = build_on_threads(scene, options, 1), four = build_on_threads(scene, options, 4);
      ASSERT_TRUE(one && four) << what;
      expect_identical(one.value(), four.value(), what);
    }
  }
}

TEST(OctreeParallel, TheTreeIsTheSerialBuildersTree) {
  // The parallel builder's numbering, child_mask()'s vertex shortcuts and the written-out
  // overlap test against the plain recursion with the generic test.
  for (const char* name : {"stadium", "soup", "cornell"}) {
    const Scene scene = make_procedural_scene(name).value();
    for (const auto& [label, options] : parallel_cases()) {
      const std::string what = std::string(name) + " " + label;
      auto built = build_octree(scene, options);
      ASSERT_TRUE(built) << what;
      expect_identical(built.value(), ReferenceOctreeBuilder(scene, options).run(), what);
    }
  }
  const std::string bunny = testing::shared_scene_path("bunny.obj");
  if (auto scene = load_obj(bunny)) {
    OctreeBuildOptions options;
    expect_identical(build_octree(scene.value(), options).value(), ReferenceOctreeBuilder(scene.value(), options).run(),
                     "bunny");
  }
}

TEST(OctreeParallel, LimitErrorsDoNotDependOnTheThreadCount) {
  const Scene scene = make_procedural_scene("stadium").value();
  OctreeBuildOptions options;
  options.max_prims = 1;
  options.max_depth = 40;
  for (const auto& [nodes, refs] : {std::pair<size_t, size_t>{3000, size_t(1) << 27}, {size_t(1) << 25, 30000},
                                    {3000, 30000}}) {
    options.node_limit = nodes;
    options.reference_limit = refs;
    auto one = build_on_threads(scene, options, 1), four = build_on_threads(scene, options, 4);
    ASSERT_FALSE(one);
    ASSERT_FALSE(four);
    EXPECT_EQ(one.error().message, four.error().message);
  }
}

}  // namespace
}  // namespace accel
