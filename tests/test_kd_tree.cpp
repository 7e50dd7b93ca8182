// kd-tree: every option against the double-precision reference (structure suite), hand-checked
// traces of the near/far traversal on tiny scenes, rays lying in split planes, parameter
// validation, the build budget, and builds that do not depend on the thread count.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <sstream>

#include <tbb/task_arena.h>

#include "batch.h"
#include "structures/kd_builder.h"
#include "structures/kd_tree.h"
#include "oracle.h"
#include "random.h"
#include "registry.h"
#include "structure_suite.h"
#include "test_support.h"

namespace accel {
namespace testing {

INSTANTIATE_TEST_SUITE_P(
    KdTree, StructureVsReference,
    ::testing::Values(SuiteCase{"kdtree", {}},                                                  // sah, defaults
                      SuiteCase{"kdtree", {"split=sah", "clip=off", "leaf_size=4"}},           //
                      SuiteCase{"kdtree", {"split=sah", "ci=80", "empty_bonus=0.5"}},          // pbrt's constants
                      SuiteCase{"kdtree", {"split=sah", "ci=4", "empty_bonus=0.5", "max_depth=32"}},  // deep
                      SuiteCase{"kdtree", {"split=sah", "ct=4", "empty_bonus=0", "leaf_size=16"}},  // shallow
                      SuiteCase{"kdtree", {"split=middle", "axis=longest", "leaf_size=1"}},    //
                      SuiteCase{"kdtree", {"split=middle", "axis=round_robin", "max_depth=40", "leaf_size=2"}},
                      SuiteCase{"kdtree", {"split=median", "axis=longest", "leaf_size=3"}},    //
                      SuiteCase{"kdtree", {"split=median", "axis=round_robin", "clip=off", "leaf_size=8"}},
                      SuiteCase{"kdtree", {"split=middle", "max_depth=8", "leaf_size=64"}}),
    // (The extremes -- max_depth=1, leaf_size=1024, ct=1000 ci=0.01 near brute force, and
    // max_depth=64 with ct=0.01 ci=1000 empty_bonus=0.95 -- are slow on 100k rays x 20k
    // triangles, or in the sanitizer build: KdTreeParams.ExtremesBuildAndAnswerOrFailClearly
    // runs them on smaller scenes.)
    suite_case_name);

}  // namespace testing

namespace {

using testing::make_ray;
using testing::ReferenceHit;
using testing::visited;

std::unique_ptr<Structure> build(const Scene& scene, const std::vector<std::string>& params) {
  auto built = build_structure("kdtree", scene, params);
  EXPECT_TRUE(built) << built.error().message;
  return built ? std::move(built.value()) : nullptr;
}

/// "visit 0", "push 2", ... : the recorded steps in a form that reads like the lecture.
std::string steps(const TraceRecorder& rec) {
  std::ostringstream out;
  for (const TraceEvent& e : rec.events()) {
    if (out.tellp() > 0) out << ", ";
    switch (e.kind) {
      case TraceEventKind::Visit: out << "visit " << e.node; break;
      case TraceEventKind::Push: out << "push " << e.node; break;
      case TraceEventKind::Pop: out << "pop " << e.node; break;
      case TraceEventKind::Cull:
        out << "cull " << e.node << (e.reason == CullReason::MissedBounds ? " missed" : " beyond");
        break;
      case TraceEventKind::TestPrim: out << "test " << e.prim << (e.hit ? " hit" : " miss"); break;
      case TraceEventKind::NewClosest: out << "closest " << e.prim; break;
      case TraceEventKind::Done: out << "done " << e.prim; break;
      default: out << event_kind_name(e.kind); break;
    }
  }
  return out.str();
}

// Two triangles facing the x axis: T0 in the plane x = 0.2 (the lower-left half y + z <= 1
// of the unit square), T1 in x = 0.8 (the upper-right half y + z >= 1). With split=middle,
// axis=round_robin and leaf_size=1 the tree is, by hand:
//   node 0: inner, x = 0.5 (middle of the root region x in [0.2, 0.8])
//   node 1: leaf {T0} (below, x <= 0.5)      node 2: leaf {T1} (above, x >= 0.5)
Scene two_walls() {
  return Scene({{0.2f, 0, 0}, {0.2f, 1, 0}, {0.2f, 0, 1}, {0.8f, 1, 1}, {0.8f, 0, 1}, {0.8f, 1, 0}},
               {{0, 1, 2}, {3, 4, 5}}, "two_walls");
}
const std::vector<std::string> kHandParams = {"split=middle", "axis=round_robin", "leaf_size=1"};

TEST(KdTreeTrace, HandBuiltTreeHasTheExpectedLayout) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  const auto& kd = static_cast<const KdTree&>(*s);
  ASSERT_EQ(kd.data().nodes.size(), 3u);
  const KdNode root = kd.data().nodes[0];
  EXPECT_FALSE(root.leaf());
  EXPECT_EQ(root.axis(), 0);
  EXPECT_EQ(root.split(), 0.5f);
  EXPECT_EQ(root.above_child(), 2u);
  EXPECT_EQ(s->node_prims(1), std::vector<uint32_t>{0});
  EXPECT_EQ(s->node_prims(2), std::vector<uint32_t>{1});
  const NodeView v0 = s->node_view(0), v2 = s->node_view(2);
  EXPECT_EQ(v0.split_axis, 0);
  EXPECT_EQ(v0.split_pos, 0.5f);
  EXPECT_EQ(v2.box.min.x, 0.5f);  // the region, cut at the parent's plane
  EXPECT_EQ(v2.box.max.x, 0.8f);
  EXPECT_EQ(v2.depth, 1);
  std::vector<NodeId> ids;
  s->for_each_node([&](const NodeView& v) { ids.push_back(v.id); });
  EXPECT_EQ(ids, (std::vector<NodeId>{0, 1, 2}));
  const BuildStats st = s->build_stats();
  EXPECT_EQ(st.nodes, 3u);
  EXPECT_EQ(st.leaves, 2u);
  EXPECT_EQ(st.max_depth, 1);
  EXPECT_EQ(st.prim_references, 2u);
  EXPECT_EQ(st.memory_bytes, 3 * 8 + 2 * 4u);
  // SAH cost by hand (ct = ci = 1): root region 0.6 x 1 x 1 (area 2*(0.6+1+0.6) = 4.4),
  // children 0.3 x 1 x 1 (area 2*(0.3+1+0.3) = 3.2): 1 + 2 * 1 * 1 * 3.2/4.4.
  EXPECT_NEAR(st.sah_cost, 1.0 + 2.0 * 3.2 / 4.4, 1e-5);
  EXPECT_EQ(st.sah_ct, 1.0);
  EXPECT_EQ(st.sah_ci, 1.0);
}

TEST(KdTreeTrace, RayAlongPlusXVisitsBelowThenAbove) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  // Misses T0 (y + z = 1.5 > 1), hits T1 at x = 0.8: t = 1.8. The plane x = 0.5 is at t = 1.5.
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({-1.0f, 0.75f, 0.75f}, {1, 0, 0}), rec);
  EXPECT_EQ(h.prim, 1);
  EXPECT_FLOAT_EQ(h.t, 1.8f);
  EXPECT_EQ(steps(rec), "visit 0, push 2, visit 1, test 0 miss, pop 2, visit 2, test 1 hit, closest 1, done 1");
  EXPECT_EQ(visited(rec), (std::vector<NodeId>{0, 1, 2}));
  // The near child gets [t_enter, t_split], the far one [t_split, t_exit].
  const auto& ev = rec.events();
  EXPECT_FLOAT_EQ(ev[0].t0, 1.2f);
  EXPECT_FLOAT_EQ(ev[1].t0, 1.5f);  // push key = t_split
  EXPECT_FLOAT_EQ(ev[2].t0, 1.2f);
  EXPECT_FLOAT_EQ(ev[2].t1, 1.5f);
  EXPECT_FLOAT_EQ(ev[5].t0, 1.5f);
  EXPECT_NEAR(ev[5].t1, 1.8f, 1e-5f);
}

TEST(KdTreeTrace, RayAlongMinusXVisitsAboveThenBelow) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  // Misses T1 (y + z = 0.5 < 1), hits T0 at x = 0.2: t = 1.8; the plane is at t = 1.5.
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({2.0f, 0.25f, 0.25f}, {-1, 0, 0}), rec);
  EXPECT_EQ(h.prim, 0);
  EXPECT_FLOAT_EQ(h.t, 1.8f);
  EXPECT_EQ(steps(rec), "visit 0, push 1, visit 2, test 1 miss, pop 1, visit 1, test 0 hit, closest 0, done 0");
  EXPECT_EQ(visited(rec), (std::vector<NodeId>{0, 2, 1}));
}

TEST(KdTreeTrace, EarlyExitNeverVisitsTheFarChild) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  // Hits T0 at t = 1.2 < t_split = 1.5: the pending far child is popped and culled.
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({-1.0f, 0.25f, 0.25f}, {1, 0, 0}), rec);
  EXPECT_EQ(h.prim, 0);
  EXPECT_FLOAT_EQ(h.t, 1.2f);
  EXPECT_EQ(steps(rec), "visit 0, push 2, visit 1, test 0 hit, closest 0, pop 2, cull 2 beyond, done 0");
  EXPECT_EQ(rec.events()[6].reason, CullReason::BeyondClosestHit);
  EXPECT_FLOAT_EQ(rec.events()[6].t0, 1.5f);
}

TEST(KdTreeTrace, CaseBOnlyNearSideTheFarChildIsCulled) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  // Slanted ray: x = 0.25 + 0.1 t, z = 2 - t. Inside the root region for t in [1, 2]
  // (x from 0.35 to 0.45): it reaches x = 0.5 only at t = 2.5 > t_max.
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({0.25f, 0.25f, 2.0f}, {0.1f, 0.0f, -1.0f}), rec);
  EXPECT_FALSE(h.valid());
  EXPECT_EQ(steps(rec), "visit 0, cull 2 missed, visit 1, test 0 miss, done -1");
  EXPECT_EQ(rec.events()[1].depth, 1);
  EXPECT_NEAR(rec.events()[1].t0, 2.5f, 1e-5f);  // the culled child's key is t_split

  // The same with a clipped ray: +x through both walls, but tmax = 1.3 ends before x = 0.5.
  rec.clear();
  const Hit h2 = s->intersect_traced(make_ray({-1.0f, 0.25f, 0.25f}, {1, 0, 0}, 0.0f, 1.3f), rec);
  EXPECT_EQ(h2.prim, 0);
  EXPECT_EQ(steps(rec), "visit 0, cull 2 missed, visit 1, test 0 hit, closest 0, done 0");
}

TEST(KdTreeTrace, CaseCOnlyFarSideTheNearChildIsCulled) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  // x = 0.6 + 0.2 t, z = 1.5 - t: enters the region at t = 0.5 (x = 0.7), already past
  // x = 0.5 (t_split = -0.5 < t_min); hits T1 at t = 1, point (0.8, 0.8, 0.5).
  TraceRecorder rec;
  const Hit h = s->intersect_traced(make_ray({0.6f, 0.8f, 1.5f}, {0.2f, 0.0f, -1.0f}), rec);
  EXPECT_EQ(h.prim, 1);
  EXPECT_NEAR(h.t, 1.0f, 1e-6f);
  EXPECT_EQ(steps(rec), "visit 0, cull 1 missed, visit 2, test 1 hit, closest 1, done 1");
  EXPECT_NEAR(rec.events()[1].t0, -0.5f, 1e-6f);
}

TEST(KdTreeTrace, RayOutsideTheRootRegionCullsTheRoot) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  TraceRecorder rec;
  EXPECT_FALSE(s->intersect_traced(make_ray({-1.0f, 5.0f, 0.5f}, {1, 0, 0}), rec).valid());
  EXPECT_EQ(steps(rec), "cull 0 missed, done -1");
}

// Triangles around the plane x = 0.5 of the two-walls tree (the root region stays x in
// [0.2, 0.8], so the root plane stays at 0.5):
//   T2: in the plane x = 0.5 (y, z in [0.1, 0.4]);   goes to one side only (middle: below)
//   T3: touches the plane from above with its edge x = 0.5 (z = 0.6, y in [0.2, 0.9])
//   T4: touches the plane from below with its edge x = 0.5 (z = 0.7, y in [0.2, 0.9])
//   T5: crosses the plane (z = 0.3, x in [0.4, 0.6])
Scene plane_scene() {
  std::vector<Vec3> p = {{0.2f, 0, 0}, {0.2f, 1, 0}, {0.2f, 0, 1}, {0.8f, 1, 1}, {0.8f, 0, 1}, {0.8f, 1, 0},
                         {0.5f, 0.1f, 0.1f}, {0.5f, 0.4f, 0.1f}, {0.5f, 0.1f, 0.4f},
                         {0.5f, 0.2f, 0.6f}, {0.5f, 0.9f, 0.6f}, {0.7f, 0.5f, 0.6f},
                         {0.5f, 0.2f, 0.7f}, {0.5f, 0.9f, 0.7f}, {0.3f, 0.5f, 0.7f},
                         {0.4f, 0.6f, 0.3f}, {0.6f, 0.6f, 0.3f}, {0.5f, 0.95f, 0.3f}};
  std::vector<UVec3> t = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}, {12, 13, 14}, {15, 16, 17}};
  return Scene(std::move(p), std::move(t), "plane");
}

/// Reference check of one ray; also returns the reference answer.
::testing::AssertionResult matches_reference(const Scene& scene, const Structure& s, const Ray& r,
                                             ReferenceHit* ref_out = nullptr) {
  const ReferenceHit ref = testing::reference_closest(scene, r);
  if (ref_out) *ref_out = ref;
  const Hit got = s.intersect(r);
  TraceRecorder rec;
  const Hit traced = s.intersect_traced(r, rec);
  std::string why;
  if (!testing::hit_is_correct(scene, r, got, ref, &why)) return ::testing::AssertionFailure() << why;
  if (traced.prim != got.prim || traced.t != got.t) return ::testing::AssertionFailure() << "traced answer differs";
  return ::testing::AssertionSuccess();
}

TEST(KdTreeTrace, RayLyingInTheSplitPlaneVisitsBothSides) {
  const Scene scene = plane_scene();
  for (const auto& params : {kHandParams, std::vector<std::string>{"split=sah", "leaf_size=1", "ci=4"},
                             std::vector<std::string>{"split=median", "leaf_size=1"}}) {
    SCOPED_TRACE(params[0]);
    auto s = build(scene, params);
    ASSERT_TRUE(s);
    for (float dx : {0.0f, -0.0f}) {
      SCOPED_TRACE(std::signbit(dx) ? "dir.x = -0.0" : "dir.x = +0.0");
      // Down -z in the plane x = 0.5 at y = 0.5: T4's edge (z = 0.7) is first, T3's (0.6)
      // next, T5 (0.3) crosses; T2 lies in the plane and is never hit (docs/hits.md).
      ReferenceHit ref;
      Ray down = make_ray({0.5f, 0.5f, 2.0f}, {dx, 0.0f, -1.0f});
      EXPECT_TRUE(matches_reference(scene, *s, down, &ref));
      EXPECT_EQ(ref.prim, 4);
      // Start below T4 and T3 so the crossing T5 is the answer.
      Ray low = make_ray({0.5f, 0.62f, 0.55f}, {dx, 0.0f, -1.0f});
      EXPECT_TRUE(matches_reference(scene, *s, low, &ref));
      EXPECT_EQ(ref.prim, 5);
      // In the plane, slanted: onto T3's edge (T3 touches the plane from above) and onto
      // T5 (crossing it).
      Ray onto_edge = make_ray({0.5f, 1.5f, 0.9f}, {dx, -1.0f, -0.4f});
      EXPECT_TRUE(matches_reference(scene, *s, onto_edge, &ref));
      EXPECT_EQ(ref.prim, 3);
      Ray onto_crossing = make_ray({0.5f, -1.0f, 1.0f}, {dx, 1.0f, -0.4f});
      EXPECT_TRUE(matches_reference(scene, *s, onto_crossing, &ref));
      EXPECT_EQ(ref.prim, 5);
    }
  }
  // In the hand tree: the root's NaN split distance sends the ray into both children with
  // the whole interval, below first for dir.x = +0, above first for -0.
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  for (float dx : {0.0f, -0.0f}) {
    TraceRecorder rec;
    s->intersect_traced(make_ray({0.5f, 0.5f, 2.0f}, {dx, 0.0f, -1.0f}), rec);
    const auto& ev = rec.events();
    ASSERT_GE(ev.size(), 3u);
    EXPECT_EQ(ev[0].kind, TraceEventKind::Visit);
    EXPECT_EQ(ev[1].kind, TraceEventKind::Push);
    const KdNode root = static_cast<const KdTree&>(*s).data().nodes[0];
    EXPECT_EQ(ev[1].node, std::signbit(dx) ? 1u : root.above_child());
    EXPECT_EQ(ev[1].t0, ev[0].t0) << "both children get the whole interval";
  }
}

TEST(KdTreeTrace, RayParallelToThePlaneStaysOnItsOriginSide) {
  const Scene scene = two_walls();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  for (float dx : {0.0f, -0.0f}) {
    // x = 0.3 < 0.5: only node 1 (below); x = 0.7: only node 2.
    TraceRecorder rec;
    s->intersect_traced(make_ray({0.3f, 0.5f, 2.0f}, {dx, 0.0f, -1.0f}), rec);
    EXPECT_EQ(steps(rec), "visit 0, cull 2 missed, visit 1, test 0 miss, done -1");
    rec.clear();
    s->intersect_traced(make_ray({0.7f, 0.5f, 2.0f}, {dx, 0.0f, -1.0f}), rec);
    EXPECT_EQ(steps(rec), "visit 0, cull 1 missed, visit 2, test 1 miss, done -1");
  }
}

TEST(KdTreeTrace, HitExactlyAtTheSplitDistance) {
  const Scene scene = plane_scene();
  auto s = build(scene, kHandParams);
  ASSERT_TRUE(s);
  // +x and -x through T2 (in the plane x = 0.5): the hit is at t == t_split exactly. (From
  // x = 0.25, past T0, and from x = 0.75, past T1.)
  for (const Ray& r : {make_ray({0.25f, 0.2f, 0.2f}, {1, 0, 0}), make_ray({0.75f, 0.2f, 0.2f}, {-1, 0, 0})}) {
    ReferenceHit ref;
    EXPECT_TRUE(matches_reference(scene, *s, r, &ref));
    EXPECT_EQ(ref.prim, 2);
    EXPECT_EQ(s->intersect(r).t, 0.25f);
  }
  // Origin on the plane (t_split = 0), leaving it to either side.
  for (const Ray& r : {make_ray({0.5f, 0.7f, 0.5f}, {0.25f, 0, -1}), make_ray({0.5f, 0.7f, 0.5f}, {-0.25f, 0, -1})}) {
    ReferenceHit ref;
    EXPECT_TRUE(matches_reference(scene, *s, r, &ref));
    EXPECT_EQ(ref.prim, 5);
  }
  // Crossing x = 0.5 exactly where it meets T5 (which crosses the plane): from
  // (0.3, 0.7, 0.5) towards (0.5, 0.7, 0.3), and mirrored.
  for (const Ray& r : {make_ray({0.3f, 0.7f, 0.5f}, {0.2f, 0.0f, -0.2f}), make_ray({0.7f, 0.7f, 0.5f}, {-0.2f, 0.0f, -0.2f})}) {
    ReferenceHit ref;
    EXPECT_TRUE(matches_reference(scene, *s, r, &ref));
    EXPECT_EQ(ref.prim, 5);
    EXPECT_EQ(s->intersect(r).prim, 5);
    EXPECT_FLOAT_EQ(s->intersect(r).t, 1.0f);
  }
}

// Every split plane of real trees, rays in it (origin on the plane, direction component +0
// and -0) and rays through vertices lying on it: the cases where rounding and in-plane
// assignment meet.
TEST(KdTreeRobustness, RaysInAndThroughSplitPlanesMatchReference) {
  const Scene scenes[] = {make_procedural_scene("cornell").value(), make_procedural_scene("sphere").value(),
                          plane_scene()};
  const std::vector<std::vector<std::string>> configs = {
      {}, {"clip=off", "ci=3"}, {"split=middle", "leaf_size=1"}, {"split=median", "axis=round_robin"}};
  for (const Scene& scene : scenes) {
    for (const auto& params : configs) {
      SCOPED_TRACE(scene.name() + " " + (params.empty() ? "defaults" : params[0]));
      auto s = build(scene, params);
      ASSERT_TRUE(s);
      auto brute = std::move(build_structure("brute", scene, {}).value());
      Rng rng(7);
      const Aabb b = scene.bounds();
      size_t checked = 0, wrong = 0;
      s->for_each_node([&](const NodeView& v) {
        if (v.leaf || checked > 1500) return;
        for (int i = 0; i < 6; ++i) {
          // In the plane: origin on it, direction with a signed zero along the axis.
          Vec3 o(rng.uniform(b.min.x, b.max.x), rng.uniform(b.min.y, b.max.y), rng.uniform(b.min.z, b.max.z));
          o[v.split_axis] = v.split_pos;
          Vec3 d(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
          d[v.split_axis] = (i & 1) ? -0.0f : 0.0f;
          const Ray in_plane = make_ray(o, d);
          // Through a vertex of the scene lying on the plane (SAH planes sit on vertices).
          const uint32_t prim = uint32_t(rng.uniform(0.0f, float(scene.triangle_count()) - 0.5f));
          const Vec3 target = scene.vertex(prim, i % 3);
          Vec3 from(rng.uniform(b.min.x, b.max.x), rng.uniform(b.min.y, b.max.y), rng.uniform(b.min.z, b.max.z));
          from[v.split_axis] = v.split_pos + (rng.uniform() - 0.5f) * 2.0f;
          const Ray through = make_ray(from, target - from);
          // Origin on the plane, leaving it.
          const Ray leaving = make_ray(o, Vec3(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)));
          for (const Ray& r : {in_plane, through, leaving}) {
            ++checked;
            // Near vertices the float kernel itself may disagree with the double reference
            // (brute force is then "wrong" too, and around a vertex several triangles give
            // t's a few ulps apart); the tree must then give what brute force with the same
            // kernel gives, up to those ulps.
            const auto result = matches_reference(scene, *s, r);
            const Hit got = s->intersect(r), expected = brute->intersect(r);
            const bool same_as_brute = got.valid() == expected.valid() &&
                                       (!got.valid() || std::abs(got.t - expected.t) <= 1e-5f * std::max(1.0f, expected.t));
            if (!result && !same_as_brute) {
              if (++wrong < 5) ADD_FAILURE() << result.message() << "; brute force: prim " << expected.prim << " t " << expected.t;
            }
          }
        }
      });
      if (s->build_stats().nodes > 1) {  // (sah makes the 6-triangle scene one leaf)
        EXPECT_GT(checked, 0u);
      }
      EXPECT_EQ(wrong, 0u);
    }
  }
}

TEST(KdTreeRobustness, NegativeTminAndAxisRays) {
  const Scene scene = make_procedural_scene("cornell").value();
  auto s = build(scene, {});
  ASSERT_TRUE(s);
  Rng rng(11);
  const Aabb b = scene.bounds();
  for (int i = 0; i < 3000; ++i) {
    const Vec3 o(rng.uniform(b.min.x, b.max.x), rng.uniform(b.min.y, b.max.y), rng.uniform(b.min.z, b.max.z));
    Vec3 d(0.0f);
    d[i % 3] = (i / 3) % 2 ? 1.0f : -1.0f;
    if (i % 5 == 0) d[(i + 1) % 3] = -0.0f;
    EXPECT_TRUE(matches_reference(scene, *s, make_ray(o, d, i % 2 ? -10.0f : 0.0f, i % 7 ? kInf : 2.0f)));
  }
}

TEST(KdTreeBuild, SahStopsWhenSplittingCostsMore) {
  // 500 identical triangles: no plane strictly inside their region separates anything.
  std::vector<UVec3> t(500, UVec3(0, 1, 2));
  const Scene same({{0, 0, 0}, {1, 0, 0}, {0, 1, 1}}, t);
  for (const char* split : {"split=sah", "split=middle", "split=median"}) {
    auto s = build(same, {split, "leaf_size=1"});
    ASSERT_TRUE(s);
    EXPECT_EQ(s->build_stats().nodes, 1u) << split;
    EXPECT_EQ(s->build_stats().prim_references, 500u) << split;
  }
  // A triangle pair far apart, both in planes on the region's boundary: SAH cuts one off
  // into a flat cell (Wald & Havran 2006 sec. 4.4).
  const Scene pair({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 10}, {1, 0, 10}, {0, 1, 10}}, {{0, 1, 2}, {3, 4, 5}});
  // Cost by hand: root region 1 x 1 x 10 (area 42); the flat cell z = 0 has area 2 and the
  // rest is the whole region: ct + ci * (2/42 * 1 + 1 * 1) < ci * 2 iff ci > ct / (1 - 2/42).
  auto s = build(pair, {"split=sah", "leaf_size=1", "ci=1.1"});
  ASSERT_TRUE(s);
  EXPECT_EQ(s->build_stats().nodes, 3u);
  EXPECT_EQ(s->node_view(0).split_axis, 2);
  // Just below that ratio, and with ci tiny relative to ct, splitting does not pay.
  for (const char* ci : {"ci=1.04", "ci=0.01"}) {
    auto flat = build(pair, {"split=sah", "leaf_size=1", ci});
    ASSERT_TRUE(flat);
    EXPECT_EQ(flat->build_stats().nodes, 1u) << ci;
    EXPECT_EQ(static_cast<const KdTree&>(*flat).data().leaf_reasons.no_gain, 1u);
  }
}

TEST(KdTreeBuild, PerfectSplitsStoreFewerReferences) {
  const Scene scene = make_procedural_scene("sphere").value();
  auto clipped = build(scene, {"clip=on"});
  auto unclipped = build(scene, {"clip=off"});
  ASSERT_TRUE(clipped && unclipped);
  EXPECT_LT(clipped->build_stats().sah_cost, unclipped->build_stats().sah_cost);
}

TEST(KdTreeBuild, StatsAreConsistent) {
  const Scene scene = make_procedural_scene("sphere").value();
  for (const char* split : {"split=sah", "split=middle", "split=median"}) {
    auto s = build(scene, {split});
    ASSERT_TRUE(s);
    const BuildStats st = s->build_stats();
    size_t nodes = 0, leaves = 0, refs = 0;
    int depth = 0;
    s->for_each_node([&](const NodeView& v) {
      EXPECT_EQ(v.id, nodes) << "pre-order ids";
      ++nodes;
      depth = std::max(depth, v.depth);
      if (v.leaf) {
        ++leaves;
        refs += v.prim_count;
        EXPECT_EQ(s->node_prims(v.id).size(), v.prim_count);
      } else {
        EXPECT_GE(v.split_pos, v.box.min[v.split_axis]);  // == only for sah's flat cells
        EXPECT_LE(v.split_pos, v.box.max[v.split_axis]);
      }
      const NodeView again = s->node_view(v.id);
      EXPECT_EQ(again.depth, v.depth);
      EXPECT_EQ(again.box.min, v.box.min);
      EXPECT_EQ(again.box.max, v.box.max);
    });
    EXPECT_EQ(st.nodes, nodes);
    EXPECT_EQ(st.leaves, leaves);
    EXPECT_EQ(st.prim_references, refs);
    EXPECT_EQ(st.max_depth, depth);
    EXPECT_EQ(st.prims, scene.valid_prims().size());
    EXPECT_EQ(st.memory_bytes, nodes * 8 + refs * 4);
    EXPECT_LE(st.max_depth, kd_auto_max_depth(scene.valid_prims().size()));
    EXPECT_FALSE(std::isnan(st.sah_cost));
  }
  EXPECT_EQ(kd_auto_max_depth(69451), 29);  // round(8 + 1.3 * 16.08)
  EXPECT_EQ(kd_auto_max_depth(1), 8);
}

/// Everything a build produces, compared exactly (float bits included).
void expect_same_tree(const KdTreeData& a, const KdTreeData& b, const std::string& what) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << what;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes[i].payload, b.nodes[i].payload) << what << ": node " << i;
    ASSERT_EQ(a.nodes[i].bits, b.nodes[i].bits) << what << ": node " << i;
  }
  EXPECT_EQ(a.prim_ids, b.prim_ids) << what;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(std::bit_cast<uint32_t>(a.root_box.min[k]), std::bit_cast<uint32_t>(b.root_box.min[k])) << what;
    EXPECT_EQ(std::bit_cast<uint32_t>(a.root_box.max[k]), std::bit_cast<uint32_t>(b.root_box.max[k])) << what;
  }
  EXPECT_EQ(a.max_depth_limit, b.max_depth_limit) << what;
  EXPECT_EQ(a.depth, b.depth) << what;
  const KdLeafReasons &ra = a.leaf_reasons, &rb = b.leaf_reasons;
  EXPECT_EQ(std::vector<size_t>({ra.few_prims, ra.max_depth, ra.no_gain, ra.no_progress, ra.bad_refines, ra.thin}),
            std::vector<size_t>({rb.few_prims, rb.max_depth, rb.no_gain, rb.no_progress, rb.bad_refines, rb.thin}))
      << what;
}

TEST(KdTreeBuild, SameTreeOnOneAndFourThreads) {
  // The stadium's tens of thousands of triangles take the parallel path (subtree tasks from
  // 2048 triangles down), several levels deep.
  const Scene scene = make_procedural_scene("stadium").value();
  ASSERT_GT(scene.valid_prims().size(), 8u * 2048u);
  std::vector<std::pair<std::string, KdBuildOptions>> configs;
  for (KdSplit split : {KdSplit::Sah, KdSplit::Middle, KdSplit::Median}) {
    for (bool clip : {true, false}) {
      KdBuildOptions o;
      o.split = split;
      o.clip = clip;
      configs.push_back({std::string(kd_split_name(split)) + (clip ? " clip=on" : " clip=off"), o});
    }
  }
  KdBuildOptions round_robin;
  round_robin.split = KdSplit::Median;
  round_robin.axis = KdAxis::RoundRobin;
  round_robin.max_depth = 24;
  configs.push_back({"median axis=round_robin max_depth=24", round_robin});
  for (const auto& config : configs) {
    const auto& [what, o] = config;
    const KdBuildOptions& options = o;  // clang before 16 cannot capture a structured binding
    tbb::task_arena one(1), four(4);
    auto serial = one.execute([&] { return build_kd_tree(scene, options); });
    auto parallel = four.execute([&] { return build_kd_tree(scene, options); });
    ASSERT_TRUE(serial && parallel) << what;
    EXPECT_GT(serial.value().nodes.size(), 1000u) << what;
    expect_same_tree(serial.value(), parallel.value(), what);
  }
}

TEST(KdTreeBuild, BudgetErrorsDoNotDependOnTheThreadCount) {
  // A parallel build stops at the first budget a task finds exceeded; the error returned is
  // the one the serial order meets first.
  const Scene scene = make_procedural_scene("stadium").value();
  KdBuildOptions o;
  o.split = KdSplit::Middle;
  o.max_depth = 40;
  o.node_limit = 20000;
  o.reference_limit = 30000;
  tbb::task_arena one(1), four(4);
  auto serial = one.execute([&] { return build_kd_tree(scene, o); });
  auto parallel = four.execute([&] { return build_kd_tree(scene, o); });
  ASSERT_FALSE(serial);
  ASSERT_FALSE(parallel);
  EXPECT_EQ(serial.error().message, parallel.error().message);
}

TEST(KdTreeParams, OutOfRangeValuesAreRejectedByName) {
  const Scene scene = two_walls();
  const std::pair<const char*, const char*> bad[] = {
      {"max_depth=65", "[0, 64]"}, {"max_depth=-1", "[0, 64]"}, {"leaf_size=0", "[1, 1024]"},
      {"leaf_size=1025", "[1, 1024]"}, {"ct=0", "[0.01, 1000]"}, {"ci=1e9", "[0.01, 1000]"},
      {"empty_bonus=1", "[0, 0.95]"}, {"split=best", "middle, median, sah"}, {"axis=x", "round_robin, longest"},
      {"clip=yes", "on, off"}, {"ci=nan", "[0.01, 1000]"}};
  for (const auto& [kv, range] : bad) {
    auto s = build_structure("kdtree", scene, {kv});
    ASSERT_FALSE(s) << kv;
    const std::string key = std::string(kv).substr(0, std::string(kv).find('='));
    EXPECT_NE(s.error().message.find("'" + key + "'"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find(range), std::string::npos) << s.error().message;
  }
}

TEST(KdTreeParams, BudgetErrorsNameTheParameters) {
  const Scene scene = make_procedural_scene("sphere").value();
  KdBuildOptions o;
  o.split = KdSplit::Middle;
  o.max_depth = 64;
  o.node_limit = 1000;
  auto r = build_kd_tree(scene, o);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("max_depth"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("1000 nodes"), std::string::npos) << r.error().message;
  o = KdBuildOptions{};
  o.reference_limit = 100;
  r = build_kd_tree(scene, o);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("references"), std::string::npos) << r.error().message;
}

TEST(KdTreeParams, ExtremesBuildAndAnswerOrFailClearly) {
  for (const char* name : {"sphere", "cornell"}) {
    // Own, smaller ray set: several of these configurations are near brute force.
    const auto& w = testing::workload(std::string("kd-extremes:") + name,
                                      [name] { return make_procedural_scene(name).value(); }, 3000, 40, 30);
    for (const auto& params : std::vector<std::vector<std::string>>{
             {"max_depth=1"},
             {"leaf_size=1024"},
             {"ct=1000", "ci=0.01"},
             {"split=middle", "leaf_size=1", "max_depth=64"},
             {"split=median", "leaf_size=1", "max_depth=64", "axis=round_robin"},
             {"split=sah", "leaf_size=1", "max_depth=64", "ct=0.01", "ci=1000", "empty_bonus=0.95"},
             {"split=middle", "leaf_size=1", "max_depth=64", "clip=off", "ci=1000"}}) {
      SCOPED_TRACE(std::string(name) + " " + params[0] + " " + params.back());
      auto s = build_structure("kdtree", w.scene, params);
      if (!s) {
        EXPECT_NE(s.error().message.find("kdtree parameter"), std::string::npos) << s.error().message;
        continue;
      }
      std::string failures;
      EXPECT_EQ(testing::count_wrong(w, trace_all(*s.value(), w.rays), &failures), 0u) << failures;
      EXPECT_LE(s.value()->build_stats().max_depth, kKdMaxDepth);
    }
  }
}

}  // namespace
}  // namespace accel
