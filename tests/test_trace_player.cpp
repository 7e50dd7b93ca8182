// TracePlayer (time -> step), trace_highlight (step -> what the viewer shows) and the cost
// heat map. All without a window: the viewer only draws what these return.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "heatmap.h"
#include "ray_gen.h"
#include "registry.h"
#include "scene.h"
#include "trace_events.h"
#include "trace_player.h"

namespace accel {
namespace {

using namespace testing::events;

TraceEvent cull(NodeId node, CullReason why, float t = 0.0f) {
  TraceEvent e = event(TraceEventKind::Cull, node, t, t);
  e.reason = why;
  return e;
}

/// visit 0, test 5 (hit 3), closest 5, visit 1, test 6 (hit 2), closest 6, test 7 (miss), done 6.
std::vector<TraceEvent> two_hits() {
  return {event(TraceEventKind::Visit, 0, 0.0f, 10.0f), test_prim(5, true, 3.0f), new_closest(5, 3.0f),
          event(TraceEventKind::Visit, 1, 1.0f, 4.0f),  test_prim(6, true, 2.0f), new_closest(6, 2.0f),
          test_prim(7, false),                          done(6, 2.0f)};
}

// ---------------------------------------------------------------------------------------
// TracePlayer

TEST(TracePlayer, EmptyTraceIsInert) {
  TracePlayer p;
  EXPECT_TRUE(p.empty());
  EXPECT_EQ(p.current(), nullptr);
  EXPECT_FALSE(p.step_forward());
  EXPECT_FALSE(p.step_back());
  EXPECT_FALSE(p.jump_to_end());
  p.play();
  EXPECT_FALSE(p.playing());
  EXPECT_FALSE(p.advance(10.0));
  EXPECT_EQ(p.step(), 0u);
  EXPECT_EQ(p.hit_step(), 0u);
}

TEST(TracePlayer, StepForwardBackAndClamp) {
  TracePlayer p;
  p.load(two_hits());
  EXPECT_EQ(p.size(), 8u);
  EXPECT_EQ(p.step(), 0u);
  EXPECT_EQ(p.current()->kind, TraceEventKind::Visit);
  EXPECT_TRUE(p.step_forward());
  EXPECT_EQ(p.step(), 1u);
  EXPECT_TRUE(p.step_forward(3));
  EXPECT_EQ(p.step(), 4u);
  EXPECT_TRUE(p.step_forward(100));  // clamped to the last step
  EXPECT_EQ(p.step(), 7u);
  EXPECT_TRUE(p.at_end());
  EXPECT_FALSE(p.step_forward());
  EXPECT_EQ(p.current()->kind, TraceEventKind::Done);
  EXPECT_TRUE(p.step_back(2));
  EXPECT_EQ(p.step(), 5u);
  EXPECT_TRUE(p.step_back(100));
  EXPECT_EQ(p.step(), 0u);
  EXPECT_FALSE(p.step_back());
  EXPECT_TRUE(p.jump_to_end());
  EXPECT_EQ(p.step(), 7u);
  EXPECT_TRUE(p.seek(3));
  EXPECT_FALSE(p.seek(3));
  p.reset();
  EXPECT_EQ(p.step(), 0u);
}

TEST(TracePlayer, AdvancePlaysAtSpeedAndStopsAtEnd) {
  TracePlayer p;
  p.load(two_hits());
  p.set_speed(4.0);
  EXPECT_FALSE(p.advance(1.0));  // paused: time does not count
  p.play();
  EXPECT_TRUE(p.playing());
  EXPECT_FALSE(p.advance(0.2));  // 0.8 step
  EXPECT_TRUE(p.advance(0.1));   // 1.2 steps in all: one taken, 0.2 carried
  EXPECT_EQ(p.step(), 1u);
  EXPECT_TRUE(p.advance(0.5));   // 2.2
  EXPECT_EQ(p.step(), 3u);
  p.pause();
  EXPECT_FALSE(p.advance(5.0));
  p.play();
  EXPECT_TRUE(p.advance(100.0));
  EXPECT_EQ(p.step(), 7u);
  EXPECT_FALSE(p.playing());  // stopped at the end
  p.play();                   // at the end, play starts over
  EXPECT_TRUE(p.playing());
  EXPECT_EQ(p.step(), 0u);
  p.toggle();
  EXPECT_FALSE(p.playing());
}

TEST(TracePlayer, SpeedIsClamped) {
  TracePlayer p;
  p.set_speed(0.0);
  EXPECT_EQ(p.speed(), TracePlayer::kMinSpeed);
  p.set_speed(1e9);
  EXPECT_EQ(p.speed(), TracePlayer::kMaxSpeed);
  p.set_speed(std::nan(""));
  EXPECT_EQ(p.speed(), TracePlayer::kDefaultSpeed);
  p.set_speed(10.0);
  EXPECT_EQ(p.speed(), 10.0);
}

TEST(TracePlayer, JumpToHitFindsTheNewClosestOfTheFinalHit) {
  TracePlayer p;
  p.load(two_hits());
  p.play();
  EXPECT_TRUE(p.jump_to_hit());
  EXPECT_FALSE(p.playing());
  EXPECT_EQ(p.step(), 5u);  // new closest 6, not the earlier new closest 5
  EXPECT_EQ(p.current()->kind, TraceEventKind::NewClosest);
  EXPECT_EQ(p.current()->prim, 6);

  // A miss: jump to Done.
  p.load({event(TraceEventKind::Visit, 0), test_prim(1, false), done(-1, kInf)});
  EXPECT_EQ(p.hit_step(), 2u);
  // No Done (a truncated trace): the last event.
  p.load({event(TraceEventKind::Visit, 0), test_prim(1, false)});
  EXPECT_EQ(p.hit_step(), 1u);
}

TEST(TracePlayer, ReloadKeepsTheStepClamped) {
  TracePlayer p;
  p.load(two_hits());
  p.seek(6);
  // Replay on a rebuilt structure with a shorter trace: the step is clamped to its end.
  p.load({event(TraceEventKind::Visit, 0), test_prim(1, true, 1.0f), new_closest(1, 1.0f), done(1, 1.0f)},
         /*keep_step=*/true);
  EXPECT_EQ(p.step(), 3u);
  // A longer one keeps the index.
  p.seek(2);
  p.load(two_hits(), true);
  EXPECT_EQ(p.step(), 2u);
  // A new ray starts at 0.
  p.load(two_hits(), false);
  EXPECT_EQ(p.step(), 0u);
  // An empty replay (e.g. empty scene).
  p.seek(4);
  p.load({}, true);
  EXPECT_EQ(p.step(), 0u);
  EXPECT_EQ(p.current(), nullptr);
}

// ---------------------------------------------------------------------------------------
// trace_highlight

TEST(TraceHighlight, CurrentNodeTestsAndClosest) {
  const auto events = two_hits();
  TraceHighlight h = trace_highlight(events, 0);
  ASSERT_TRUE(h.valid);
  EXPECT_EQ(h.node, 0u);
  EXPECT_EQ(h.t0, 0.0f);
  EXPECT_EQ(h.t1, 10.0f);
  EXPECT_TRUE(h.tested.empty());
  EXPECT_EQ(h.closest_prim, -1);

  h = trace_highlight(events, 2);
  ASSERT_EQ(h.tested.size(), 1u);
  EXPECT_EQ(h.tested[0].prim, 5);
  EXPECT_TRUE(h.tested[0].hit);
  EXPECT_EQ(h.closest_prim, 5);
  EXPECT_EQ(h.closest_t, 3.0f);

  h = trace_highlight(events, 6);  // in node 1: its two tests only
  EXPECT_EQ(h.visited, (std::vector<NodeId>{0, 1}));
  EXPECT_EQ(h.node, 1u);
  EXPECT_EQ(h.node_step, 3u);
  EXPECT_EQ(h.t0, 1.0f);
  EXPECT_EQ(h.t1, 4.0f);
  ASSERT_EQ(h.tested.size(), 2u);
  EXPECT_EQ(h.tested[0].prim, 6);
  EXPECT_EQ(h.tested[1].prim, 7);
  EXPECT_FALSE(h.tested[1].hit);
  EXPECT_EQ(h.closest_prim, 6);
  EXPECT_EQ(h.counters.nodes_visited, 2u);
  EXPECT_EQ(h.counters.prims_tested, 3u);
  EXPECT_FALSE(h.done);

  h = trace_highlight(events, 1000);  // clamped
  EXPECT_EQ(h.step, 7u);
  EXPECT_TRUE(h.done);
  EXPECT_EQ(h.event.kind, TraceEventKind::Done);
  EXPECT_FALSE(trace_highlight({}, 0).valid);
}

TEST(TraceHighlight, PriorityQueueContentsFromPushAndPop) {
  // The lecture's p-queue loop on a known sequence: root 0; children 1 (key 2), 2 (key 1);
  // pop 2, its children 3 (key 1.5) and 4 (key 5); pop 3 (a leaf with a hit at 1.8);
  // pop 1 (key 2 > 1.8): skipped, and the rest of the queue (4) with it.
  const std::vector<TraceEvent> ev = {
      event(TraceEventKind::Push, 0, 0.0f),                                // 0
      event(TraceEventKind::Pop, 0, 0.0f),                                 // 1
      event(TraceEventKind::Visit, 0, 0.0f, 9.0f),                         // 2
      event(TraceEventKind::Push, 1, 2.0f),                                // 3
      event(TraceEventKind::Push, 2, 1.0f),                                // 4
      event(TraceEventKind::Pop, 2, 1.0f),                                 // 5
      event(TraceEventKind::Visit, 2, 1.0f, 6.0f),                         // 6
      cull(5, CullReason::MissedBounds),                                   // 7: a child missed
      event(TraceEventKind::Push, 3, 1.5f),                                // 8
      event(TraceEventKind::Push, 4, 5.0f),                                // 9
      event(TraceEventKind::Pop, 3, 1.5f),                                 // 10
      event(TraceEventKind::Visit, 3, 1.5f, 2.5f),                         // 11
      test_prim(9, true, 1.8f),                                            // 12
      new_closest(9, 1.8f),                                                // 13
      event(TraceEventKind::Pop, 1, 2.0f),                                 // 14
      cull(1, CullReason::BeyondClosestHit, 2.0f),                         // 15
      cull(4, CullReason::BeyondClosestHit, 5.0f),                         // 16
      done(9, 1.8f),                                                       // 17
  };
  auto nodes = [](const std::vector<PendingNode>& p) {
    std::vector<NodeId> ids;
    for (const auto& n : p) ids.push_back(n.node);
    return ids;
  };
  EXPECT_EQ(nodes(trace_highlight(ev, 0).pending), (std::vector<NodeId>{0}));
  EXPECT_TRUE(trace_highlight(ev, 1).pending.empty());
  EXPECT_EQ(nodes(trace_highlight(ev, 4).pending), (std::vector<NodeId>{1, 2}));
  EXPECT_EQ(nodes(sorted_by_key(trace_highlight(ev, 4).pending)), (std::vector<NodeId>{2, 1}));
  EXPECT_EQ(nodes(trace_highlight(ev, 5).pending), (std::vector<NodeId>{1}));
  const TraceHighlight at9 = trace_highlight(ev, 9);
  EXPECT_EQ(nodes(at9.pending), (std::vector<NodeId>{1, 3, 4}));
  EXPECT_EQ(nodes(sorted_by_key(at9.pending)), (std::vector<NodeId>{3, 1, 4}));
  EXPECT_EQ(at9.pending[1].key, 1.5f);
  EXPECT_EQ(at9.counters.max_stack, 3u);
  ASSERT_EQ(at9.culled.size(), 1u);
  EXPECT_EQ(at9.culled[0].node, 5u);
  EXPECT_EQ(at9.culled[0].reason, CullReason::MissedBounds);
  EXPECT_EQ(at9.culled[0].step, 7u);
  EXPECT_EQ(nodes(trace_highlight(ev, 14).pending), (std::vector<NodeId>{4}));
  // The final sweep skips queued nodes without popping them: they leave the queue.
  const TraceHighlight end = trace_highlight(ev, 17);
  EXPECT_TRUE(end.pending.empty());
  ASSERT_EQ(end.culled.size(), 3u);
  EXPECT_EQ(end.culled[2].node, 4u);
  EXPECT_EQ(end.culled[2].reason, CullReason::BeyondClosestHit);
  EXPECT_EQ(end.culled[2].t, 5.0f);
  EXPECT_EQ(end.closest_prim, 9);
  EXPECT_EQ(end.counters.nodes_culled, 3u);
}

TEST(TraceHighlight, StackContentsFromPushAndPop) {
  // DFS order: push right (2) then left (1); pop 1; push 4, 3; pop 3.
  const std::vector<TraceEvent> ev = {
      event(TraceEventKind::Push, 2, 0.0f), event(TraceEventKind::Push, 1, 0.0f), event(TraceEventKind::Pop, 1),
      event(TraceEventKind::Push, 4, 0.0f), event(TraceEventKind::Push, 3, 0.0f), event(TraceEventKind::Pop, 3)};
  const TraceHighlight h = trace_highlight(ev, 5);
  ASSERT_EQ(h.pending.size(), 2u);
  EXPECT_EQ(h.pending[0].node, 2u);  // bottom of the stack
  EXPECT_EQ(h.pending[1].node, 4u);  // top: popped next
}

// ---------------------------------------------------------------------------------------
// With real traversals: the player replays what intersect_traced recorded.

Scene sphere_scene() {
  auto s = make_procedural_scene("sphere");
  EXPECT_TRUE(s.ok());
  return std::move(s.value());
}

Ray ray_through_sphere() {
  Ray r;
  r.org = Vec3(0.13f, 0.21f, 5.0f);
  r.dir = glm::normalize(Vec3(-0.02f, -0.03f, -1.0f));
  return r;
}

TEST(TraceReplay, EveryStructureEndsOnItsHit) {
  const Scene scene = sphere_scene();
  const Ray ray = ray_through_sphere();
  for (const auto& info : structure_registry()) {
    SCOPED_TRACE(info.name);
    auto built = build_structure(info.name, scene, {});
    ASSERT_TRUE(built.ok()) << built.error().message;
    const Hit expected = built.value()->intersect(ray);
    TraceRecorder rec;
    const Hit traced = built.value()->intersect_traced(ray, rec);
    EXPECT_EQ(traced.prim, expected.prim);
    ASSERT_FALSE(rec.events().empty());
    TracePlayer p;
    p.load(rec.events());
    p.jump_to_end();
    const TraceHighlight end = trace_highlight(rec.events(), p.step());
    EXPECT_TRUE(end.done);
    EXPECT_EQ(end.closest_prim, expected.prim);
    if (expected.valid()) {
      EXPECT_EQ(end.closest_t, expected.t);
      const size_t hs = p.hit_step();
      EXPECT_EQ(rec.events()[hs].kind, TraceEventKind::NewClosest);
      EXPECT_EQ(trace_highlight(rec.events(), hs).closest_prim, expected.prim);
    }
    const QueryStats s = rec.stats();
    EXPECT_EQ(end.counters.nodes_visited, s.nodes_visited);
    EXPECT_EQ(end.counters.nodes_culled, s.nodes_culled);
    EXPECT_EQ(end.counters.prims_tested, s.prims_tested);
  }
}

TEST(TraceReplay, PriorityQueueEndsEmptyAndPopsInKeyOrder) {
  const Scene scene = sphere_scene();
  for (const char* name : {"bvh", "spheretree"}) {
    SCOPED_TRACE(name);
    auto built = build_structure(name, scene, {"traversal=pqueue", "leaf_size=2"});
    ASSERT_TRUE(built.ok()) << built.error().message;
    TraceRecorder rec;
    built.value()->intersect_traced(ray_through_sphere(), rec);
    const auto& ev = rec.events();
    // At every pop, the popped node was the pending node with the smallest key.
    for (size_t i = 1; i < ev.size(); ++i) {
      if (ev[i].kind != TraceEventKind::Pop) continue;
      const auto before = sorted_by_key(trace_highlight(ev, i - 1).pending);
      ASSERT_FALSE(before.empty());
      EXPECT_EQ(before.front().key, ev[i].t0) << "step " << i;
    }
    EXPECT_TRUE(trace_highlight(ev, ev.size() - 1).pending.empty());
  }
}

TEST(TraceReplay, ReplayAfterRebuildKeepsTheStepClamped) {
  const Scene scene = sphere_scene();
  const Ray ray = ray_through_sphere();
  // Two traces of different lengths (the test's premise): wide leaves of up to 16 against
  // the binary tree's single triangles.
  auto coarse = build_structure("bvh", scene, {"leaf_size=16"});
  auto fine = build_structure("bvh", scene, {"leaf_size=1", "width=2"});
  ASSERT_TRUE(coarse.ok() && fine.ok());
  TraceRecorder a, b;
  coarse.value()->intersect_traced(ray, a);
  fine.value()->intersect_traced(ray, b);
  ASSERT_NE(a.events().size(), b.events().size());
  TracePlayer p;
  p.load(a.events());
  p.jump_to_end();
  const size_t old_step = p.step();
  p.load(b.events(), /*keep_step=*/true);
  EXPECT_EQ(p.step(), std::min(old_step, b.events().size() - 1));
  EXPECT_LT(p.step(), p.size());
}

// ---------------------------------------------------------------------------------------
// Heat map

TEST(CostImage, BruteForceTestsEveryTriangleAtEveryPixel) {
  const Scene scene = sphere_scene();
  auto brute = build_structure("brute", scene, {});
  ASSERT_TRUE(brute.ok());
  const PinholeCamera cam = default_camera(scene.bounds());
  const CostImage prims = compute_cost_image(*brute.value(), cam, 16, 9, CostMetric::PrimsTested);
  EXPECT_TRUE(prims.complete);
  ASSERT_EQ(prims.width, 16);
  ASSERT_EQ(prims.height, 9);
  ASSERT_EQ(prims.values.size(), 16u * 9u);
  for (float v : prims.values) EXPECT_EQ(v, float(scene.valid_prims().size()));
  EXPECT_EQ(prims.min_value, prims.max_value);
  EXPECT_EQ(prims.p99_value, prims.max_value);
  const CostImage nodes = compute_cost_image(*brute.value(), cam, 4, 3, CostMetric::NodesVisited);
  for (float v : nodes.values) EXPECT_EQ(v, 1.0f);
}

TEST(CostImage, MatchesPerRayQueryStats) {
  const Scene scene = sphere_scene();
  auto bvh = build_structure("bvh", scene, {});
  ASSERT_TRUE(bvh.ok());
  const PinholeCamera cam = default_camera(scene.bounds());
  const int w = 24, h = 18;
  for (CostMetric m : {CostMetric::NodesVisited, CostMetric::PrimsTested}) {
    const CostImage img = compute_cost_image(*bvh.value(), cam, w, h, m);
    float lo = kInf, hi = 0.0f;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        QueryStats s;
        bvh.value()->intersect(camera_ray(cam, float(x) + 0.5f, float(y) + 0.5f, w, h), &s);
        const float expected = float(m == CostMetric::NodesVisited ? s.nodes_visited : s.prims_tested);
        EXPECT_EQ(img.at(x, y), expected) << x << "," << y;
        lo = std::min(lo, expected);
        hi = std::max(hi, expected);
      }
    }
    EXPECT_EQ(img.min_value, lo);
    EXPECT_EQ(img.max_value, hi);
    EXPECT_LE(img.p99_value, img.max_value);
    EXPECT_GE(img.p99_value, img.min_value);
    EXPECT_GT(img.max_value, 0.0f);
  }
}

TEST(CostImage, EmptySizeAndCancel) {
  const Scene scene = sphere_scene();
  auto bvh = build_structure("bvh", scene, {});
  ASSERT_TRUE(bvh.ok());
  const PinholeCamera cam = default_camera(scene.bounds());
  const CostImage empty = compute_cost_image(*bvh.value(), cam, 0, 10, CostMetric::NodesVisited);
  EXPECT_TRUE(empty.values.empty());
  EXPECT_TRUE(empty.complete);
  const std::atomic<bool> cancelled{true};
  const CostImage stopped = compute_cost_image(*bvh.value(), cam, 32, 32, CostMetric::NodesVisited, &cancelled);
  EXPECT_FALSE(stopped.complete);
  EXPECT_EQ(stopped.values.size(), 32u * 32u);
  CostMetric m;
  EXPECT_TRUE(parse_cost_metric("prims", &m));
  EXPECT_EQ(m, CostMetric::PrimsTested);
  EXPECT_EQ(cost_metric_name(m), "prims");
  EXPECT_FALSE(parse_cost_metric("bogus", &m));
}

}  // namespace
}  // namespace accel
