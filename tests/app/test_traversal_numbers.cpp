// The numbers of the "Variables" panel, the t-axis strip and print-vars: they are the
// recorded ones (vars, push keys, closest hit), selected per step and never recomputed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "built_structure.h"
#include "tools/debug_ray.h"
#include "tools/traversal_numbers.h"
#include "traps.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using test::scene_of;
using test::sphere_ray;

struct Traced {
  BuiltPtr built;
  DebugRay ray;
};

Traced trace(const std::string& scene, const std::string& structure, std::vector<std::string> params,
             const accel::Ray& r) {
  Traced t;
  StructureRequest req;
  req.name = structure;
  req.params = std::move(params);
  auto built = build_structure_now(scene_of(scene), req);
  EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
  if (!built.ok()) return t;
  t.built = built.value();
  t.ray.active = true;
  t.ray.ray = r;
  t.ray.record(*t.built->structure, false);
  return t;
}

Traced trace_trap(const std::string& name) {
  auto found = accel::trap_demo(name);
  EXPECT_TRUE(found.ok());
  const accel::TrapDemo& demo = found.value();
  return trace(demo.scene.substr(std::string("procedural:").size()), demo.structure, demo.params, demo.ray);
}

size_t first_step_of(const DebugRay& ray, auto pred) {
  const auto& ev = ray.player.events();
  for (size_t i = 0; i < ev.size(); ++i)
    if (pred(i)) return i;
  return ev.size();
}

TEST(TraversalNumbers, GridStepNamesTheDdaVariablesAsRecorded) {
  Traced t = trace_trap("grid");
  ASSERT_TRUE(t.built);
  const auto& ev = t.ray.player.events();
  const size_t cell = first_step_of(t.ray, [&](size_t i) { return ev[i].kind == accel::TraceEventKind::EnterCell; });
  ASSERT_LT(cell, ev.size());
  const std::string line = vars_line(t.ray.vars, ev, accel::trace_highlight(ev, cell), t.built->kind);
  EXPECT_EQ(line.rfind("vars: X=0 Y=0 Z=0 ", 0), 0u) << line;
  EXPECT_NE(line.find(" tMaxX="), std::string::npos) << line;
  EXPECT_NE(line.find(" next=x"), std::string::npos) << line;
  EXPECT_NE(line.find(" closest_hit=inf"), std::string::npos) << line;
  EXPECT_EQ(line.find("stack="), std::string::npos) << "the grid keeps no stack: " << line;
  // The value printed is the recorded one.
  const auto* v = std::get_if<accel::GridDdaVars>(accel::vars_at(ev, t.ray.vars, cell));
  ASSERT_NE(v, nullptr);
  char expect[64];
  std::snprintf(expect, sizeof expect, " tMaxX=%g ", static_cast<double>(v->t_max[0]));
  EXPECT_NE(line.find(expect), std::string::npos) << line;
}

TEST(TraversalNumbers, KdStepNamesTheCaseAndTheStack) {
  Traced t = trace_trap("kd");
  ASSERT_TRUE(t.built);
  const auto& ev = t.ray.player.events();
  // The root's split record follows the root's visit.
  const size_t split = first_step_of(t.ray, [&](size_t i) {
    const accel::StepVars* v = accel::vars_at(ev, t.ray.vars, i);
    return v && std::holds_alternative<accel::KdSplitVars>(*v);
  });
  ASSERT_LT(split, ev.size());
  const std::string line = vars_line(t.ray.vars, ev, accel::trace_highlight(ev, split), t.built->kind);
  EXPECT_NE(line.find(" case="), std::string::npos) << line;
  EXPECT_NE(line.find(" t_split="), std::string::npos) << line;
  EXPECT_NE(line.find(" stack="), std::string::npos) << line;
}

TEST(TraversalNumbers, PqueueListsTheQueueNearestFirstWithTheRecordedKeys) {
  Traced t = trace_trap("pq");
  ASSERT_TRUE(t.built);
  ASSERT_EQ(t.built->kind, TraversalKind::HierarchyPqueue);
  const auto& ev = t.ray.player.events();
  bool saw_two = false;
  for (size_t i = 0; i < ev.size(); ++i) {
    const accel::TraceHighlight h = accel::trace_highlight(ev, i);
    const std::vector<accel::PendingNode> q = pending_in_pop_order(h, t.built->kind);
    EXPECT_TRUE(std::is_sorted(q.begin(), q.end(), [](auto& a, auto& b) { return a.key < b.key; }));
    const std::string line = vars_line(t.ray.vars, ev, h, t.built->kind);
    EXPECT_NE(line.find(" queue="), std::string::npos) << line;
    if (q.size() >= 2) {
      saw_two = true;
      char first[64];
      std::snprintf(first, sizeof first, " queue=%u:%.9g,", q[0].node, static_cast<double>(q[0].key));
      EXPECT_NE(line.find(first), std::string::npos) << line;
    }
    if (q.empty()) {
      EXPECT_NE(line.find(" queue=-"), std::string::npos) << line;
    }
  }
  EXPECT_TRUE(saw_two) << "the trap's queue holds both children at some step";
}

TEST(TraversalNumbers, StackIsListedTopFirst) {
  Traced t = trace("sphere", "bvh", {"width=2", "leaf_size=1", "traversal=ordered"}, sphere_ray());
  ASSERT_TRUE(t.built);
  const auto& ev = t.ray.player.events();
  for (size_t i = 0; i < ev.size(); ++i) {
    if (ev[i].kind != accel::TraceEventKind::Push) continue;
    // Right after a push the top of the stack is the node just pushed.
    const accel::TraceHighlight h = accel::trace_highlight(ev, i);
    const auto s = pending_in_pop_order(h, t.built->kind);
    ASSERT_FALSE(s.empty());
    EXPECT_EQ(s.front().node, ev[i].node);
    EXPECT_EQ(s.front().key, ev[i].t0);
  }
}

TEST(TraversalNumbers, StripHoldsEveryVisitedIntervalAndThePendingKeys) {
  Traced t = trace("sphere", "bvh", {"width=2", "leaf_size=1", "traversal=pqueue"}, sphere_ray());
  ASSERT_TRUE(t.built);
  const auto& ev = t.ray.player.events();
  float lo = 0, hi = 0;
  t_strip_range(ev, t.ray.ray.tmin, lo, hi);
  EXPECT_GE(lo, t.ray.ray.tmin);
  for (const accel::TraceEvent& e : ev) {
    if (e.kind == accel::TraceEventKind::Visit) {
      EXPECT_LE(lo, e.t0) << "every interval starts on the axis";
    }
  }
  for (size_t step : {size_t(0), ev.size() / 3, ev.size() / 2, ev.size() - 1}) {
    const accel::TraceHighlight h = accel::trace_highlight(ev, step);
    const TStrip s = t_strip_at(ev, t.ray.vars, h, lo, hi);
    size_t visits = 0, pushes = 0;
    for (size_t i = 0; i <= step; ++i) {
      visits += ev[i].kind == accel::TraceEventKind::Visit;
      pushes += ev[i].kind == accel::TraceEventKind::Push;
    }
    EXPECT_EQ(s.intervals.size(), visits);
    EXPECT_EQ(s.keys.size(), pushes);
    EXPECT_EQ(static_cast<size_t>(std::count_if(s.keys.begin(), s.keys.end(), [](auto& k) { return k.pending; })),
              h.pending.size());
    EXPECT_EQ(std::count_if(s.intervals.begin(), s.intervals.end(), [](auto& iv) { return iv.current; }),
              h.node == accel::kNoNode ? 0 : 1);
    for (const TStrip::Interval& iv : s.intervals) {
      if (std::isfinite(iv.t1)) {
        EXPECT_LE(iv.t1, hi);
      }
    }
    EXPECT_EQ(s.closest, h.closest_t);
  }
  // At the end the closest hit is the answer.
  const TStrip end = t_strip_at(ev, t.ray.vars, accel::trace_highlight(ev, ev.size() - 1), lo, hi);
  EXPECT_EQ(end.closest, t.ray.hit.t);
  EXPECT_LE(t.ray.hit.t, hi);
}

TEST(TraversalNumbers, KdStripHasTheRecordedSplitDistances) {
  Traced t = trace_trap("kd");
  ASSERT_TRUE(t.built);
  const auto& ev = t.ray.player.events();
  float lo = 0, hi = 0;
  t_strip_range(ev, t.ray.ray.tmin, lo, hi);
  const TStrip s = t_strip_at(ev, t.ray.vars, accel::trace_highlight(ev, ev.size() - 1), lo, hi);
  ASSERT_FALSE(s.splits.empty());
  const auto* first = std::get_if<accel::KdSplitVars>(&t.ray.vars.front().vars);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(s.splits.front().t, first->t_split);
}

}  // namespace
}  // namespace viz
