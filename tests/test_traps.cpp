// The lecture's traps (traps.h): on each demonstration's scene and ray the naive "stop at the
// first leaf with a hit" answer, computed from the real traversal's recorded steps, is
// wrong, while the real traversal agrees with brute force; and each trap is the one named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "accuracy.h"
#include "registry.h"
#include "scene.h"
#include "structures/kd_tree.h"
#include "trace_events.h"
#include "traps.h"

namespace accel {
namespace {

/// A demonstration built as accelviz-cli builds it: its scene spec, then its structure and
/// parameters through the registry.
struct BuiltTrap {
  TrapDemo demo;
  std::unique_ptr<Scene> scene;  // heap: the structure keeps a reference to it
  std::unique_ptr<Structure> structure;
};

BuiltTrap build_trap(const std::string& name) {
  BuiltTrap b;
  auto demo = trap_demo(name);
  EXPECT_TRUE(demo.ok()) << (demo.ok() ? "" : demo.error().message);
  if (!demo) return b;
  b.demo = demo.value();
  auto scene = load_scene(b.demo.scene);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
  if (!scene) return b;
  b.scene = std::make_unique<Scene>(std::move(scene.value()));
  auto built = build_structure(b.demo.structure, *b.scene, b.demo.params);
  EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
  if (built) b.structure = std::move(built.value());
  return b;
}

/// Index of the last event of `kind` at or before `step` (events.size() if none).
size_t last_before(const std::vector<TraceEvent>& events, size_t step, TraceEventKind kind) {
  for (size_t i = std::min(step + 1, events.size()); i-- > 0;)
    if (events[i].kind == kind) return i;
  return events.size();
}

/// A trap's structure with its ray traced: the events, the answer and the naive answer.
struct TracedTrap {
  BuiltTrap b;
  TraceRecorder rec;
  Hit correct;
  NaiveAnswer naive;
};

TracedTrap trace_trap(const std::string& name) {
  TracedTrap t;
  t.b = build_trap(name);
  if (!t.b.structure) return t;
  t.correct = t.b.structure->intersect_traced(t.b.demo.ray, t.rec);
  t.naive = naive_first_leaf_hit(t.rec.events());
  return t;
}

/// The step that set the answer: the last NewClosest of triangle `prim` (events.size() if none).
size_t answer_step(const std::vector<TraceEvent>& events, int32_t prim) {
  size_t step = events.size();
  for (size_t i = 0; i < events.size(); ++i)
    if (events[i].kind == TraceEventKind::NewClosest && events[i].prim == prim) step = i;
  return step;
}

/// The triangles of every leaf below `node` (node included), through node_children.
std::vector<uint32_t> subtree_prims(const Structure& s, NodeId node) {
  std::vector<uint32_t> prims;
  std::vector<NodeId> todo{node};
  while (!todo.empty()) {
    const NodeId n = todo.back();
    todo.pop_back();
    const auto here = s.node_prims(n);
    prims.insert(prims.end(), here.begin(), here.end());
    for (NodeId c : s.node_children(n)) todo.push_back(c);
  }
  return prims;
}

bool contains(const std::vector<uint32_t>& v, int32_t prim) {
  return std::find(v.begin(), v.end(), uint32_t(prim)) != v.end();
}

class Trap : public ::testing::TestWithParam<std::string> {};

TEST_P(Trap, NaiveAnswerIsWrongAndTheRealOneMatchesBruteForce) {
  const BuiltTrap b = build_trap(GetParam());
  ASSERT_TRUE(b.structure);
  EXPECT_EQ(b.demo.name, GetParam());
  EXPECT_FALSE(b.demo.title.empty());
  EXPECT_FALSE(b.demo.explanation.empty());
  EXPECT_EQ(b.structure->name(), b.demo.structure);
  const Ray& ray = b.demo.ray;
  EXPECT_EQ(ray.tmin, 0.0f);
  EXPECT_EQ(ray.tmax, kInf);
  // The viewer frames the scene's box: the ray must cross it to be seen doing anything.
  float t0 = 0, t1 = 0;
  EXPECT_TRUE(BoxTester(ray).intersect(b.scene->bounds(), ray.tmin, ray.tmax, &t0, &t1));

  TraceRecorder rec;
  const Hit correct = b.structure->intersect_traced(ray, rec);
  const Hit fast = b.structure->intersect(ray);
  EXPECT_EQ(fast.prim, correct.prim);
  EXPECT_EQ(fast.t, correct.t);

  auto brute = build_structure("brute", *b.scene, {});
  ASSERT_TRUE(brute.ok());
  const Hit oracle = brute.value()->intersect(ray);
  ASSERT_TRUE(oracle.valid());
  EXPECT_EQ(correct.prim, oracle.prim);
  EXPECT_EQ(correct.t, oracle.t);
  EXPECT_EQ(judge_hit(*b.scene, ray, correct, reference_closest(*b.scene, ray)), HitVerdict::Correct);

  const NaiveAnswer naive = naive_first_leaf_hit(rec.events());
  ASSERT_TRUE(naive.hit);
  EXPECT_NE(naive.prim, correct.prim);
  EXPECT_GT(naive.t, correct.t);
  ASSERT_LT(naive.stop_step, rec.events().size());
  EXPECT_EQ(rec.events()[naive.stop_step].kind, TraceEventKind::TestPrim);
  char expected_line[64];
  std::snprintf(expected_line, sizeof expected_line, "naive hit %d %.9g", naive.prim, double(naive.t));
  EXPECT_EQ(naive_line(naive), expected_line);
}

INSTANTIATE_TEST_SUITE_P(All, Trap, ::testing::ValuesIn(trap_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(Traps, NamesAreTheThreeTraps) {
  EXPECT_EQ(trap_names(), (std::vector<std::string>{"pq", "kd", "grid"}));
}

// pq: the naive traversal stops in the leaf entered first; the nearer hit lies in a leaf
// popped after it, whose key (entry distance) is below the naive hit.
TEST(Traps, PqNearestBoxDoesNotHoldTheNearestHit) {
  const TracedTrap t = trace_trap("pq");
  ASSERT_TRUE(t.b.structure);
  const BuiltTrap& b = t.b;
  const auto& ev = t.rec.events();
  const Hit& correct = t.correct;
  const NaiveAnswer& naive = t.naive;
  ASSERT_TRUE(naive.hit);
  const size_t naive_visit = last_before(ev, naive.stop_step, TraceEventKind::Visit);
  ASSERT_LT(naive_visit, ev.size());
  const NodeId naive_leaf = ev[naive_visit].node;
  EXPECT_TRUE(b.structure->node_view(naive_leaf).leaf);
  const size_t answered = answer_step(ev, correct.prim);
  ASSERT_LT(answered, ev.size());
  const size_t correct_visit = last_before(ev, answered, TraceEventKind::Visit);
  ASSERT_LT(correct_visit, ev.size());
  const NodeId correct_leaf = ev[correct_visit].node;
  EXPECT_NE(correct_leaf, naive_leaf);
  EXPECT_TRUE(b.structure->node_view(correct_leaf).leaf);
  const size_t correct_pop = last_before(ev, correct_visit, TraceEventKind::Pop);
  const size_t naive_pop = last_before(ev, naive_visit, TraceEventKind::Pop);
  ASSERT_LT(correct_pop, ev.size());
  ASSERT_LT(naive_pop, ev.size());
  EXPECT_EQ(ev[correct_pop].node, correct_leaf);
  EXPECT_EQ(ev[naive_pop].node, naive_leaf);
  EXPECT_GT(correct_pop, naive_visit);
  EXPECT_LT(ev[correct_pop].t0, naive.t);             // still worth popping after the naive hit
  EXPECT_LT(ev[naive_pop].t0, ev[correct_pop].t0);    // the naive leaf's box is entered first
}

// kd: the naive triangle straddles the root's split plane (it is in leaves on both sides),
// and the naive hit lies beyond t_split, in the far child's region.
TEST(Traps, KdStraddlerHitBeyondTheSplitPlane) {
  const BuiltTrap b = build_trap("kd");
  ASSERT_TRUE(b.structure);
  const auto* kd = dynamic_cast<const KdTree*>(b.structure.get());
  ASSERT_NE(kd, nullptr);
  TraceRecorder rec;
  const Hit correct = b.structure->intersect_traced(b.demo.ray, rec);
  const NaiveAnswer naive = naive_first_leaf_hit(rec.events());
  ASSERT_TRUE(naive.hit);
  const NodeView root = kd->node_view(0);
  ASSERT_FALSE(root.leaf);
  ASSERT_EQ(kd->node_children(0).size(), 2u);

  // The split the ray met with both children (case a), recorded at the root's visit.
  const KdSplitVars* split = nullptr;
  for (const RecordedVars& r : rec.recorded_vars())
    if (const auto* v = std::get_if<KdSplitVars>(&r.vars); v && v->kase == KdCase::Both) {
      ASSERT_EQ(rec.events()[r.event].kind, TraceEventKind::Visit);
      EXPECT_EQ(rec.events()[r.event].node, 0u);
      split = v;
      break;
    }
  ASSERT_NE(split, nullptr);
  EXPECT_EQ(split->axis, root.split_axis);
  const std::vector<uint32_t> near = subtree_prims(*kd, split->near_child);
  const std::vector<uint32_t> far = subtree_prims(*kd, split->far_child);
  EXPECT_TRUE(contains(near, naive.prim)) << "the naive triangle is in the near child";
  EXPECT_TRUE(contains(far, naive.prim)) << "... and in the far one: it straddles the plane";
  EXPECT_FALSE(contains(near, correct.prim)) << "the nearer triangle waits in the far child only";
  EXPECT_TRUE(contains(far, correct.prim));
  EXPECT_GT(naive.t, split->t_split);
  EXPECT_GE(correct.t, split->t_split);
  // The naive stop is the near leaf.
  const size_t visit = last_before(rec.events(), naive.stop_step, TraceEventKind::Visit);
  ASSERT_LT(visit, rec.events().size());
  EXPECT_EQ(rec.events()[visit].node, split->near_child);
}

// grid: the naive hit lies beyond the exit of the cell in which the naive walk stopped.
TEST(Traps, GridHitBeyondTheCell) {
  const TracedTrap t = trace_trap("grid");
  ASSERT_TRUE(t.b.structure);
  const auto& ev = t.rec.events();
  const Hit& correct = t.correct;
  const NaiveAnswer& naive = t.naive;
  ASSERT_TRUE(naive.hit);
  const size_t cell = last_before(ev, naive.stop_step, TraceEventKind::EnterCell);
  ASSERT_LT(cell, ev.size());
  EXPECT_GT(naive.t, ev[cell].t1);
  // The right answer is found in a later cell, which holds the naive hit's point as well.
  const size_t later = last_before(ev, answer_step(ev, correct.prim), TraceEventKind::EnterCell);
  ASSERT_LT(later, ev.size());
  EXPECT_GT(later, cell);
  EXPECT_LE(ev[later].t0, correct.t);
  EXPECT_GE(ev[later].t1, correct.t);
}

TEST(Traps, UnknownNameIsAnErrorNamingTheValidOnes) {
  auto demo = trap_demo("nope");
  ASSERT_FALSE(demo.ok());
  const std::string& m = demo.error().message;
  EXPECT_NE(m.find("nope"), std::string::npos) << m;
  for (const std::string& name : trap_names()) EXPECT_NE(m.find(name), std::string::npos) << m;
  EXPECT_FALSE(make_trap_scene("nope").ok());
  EXPECT_FALSE(make_procedural_scene("trap_nope").ok());
}

TEST(Traps, ProceduralScenesKnowTheTrapsButDoNotListThem) {
  auto scene = make_procedural_scene("trap_kd");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene.value().name(), "procedural:trap_kd");
  EXPECT_GT(scene.value().valid_prims().size(), 1u);
  for (const std::string& name : trap_names()) {
    EXPECT_TRUE(make_procedural_scene("trap_" + name).ok()) << name;
    EXPECT_TRUE(load_scene("procedural:trap_" + name).ok()) << name;
    EXPECT_FALSE(procedural_scene_description("trap_" + name).empty()) << name;
  }
  for (const std::string& name : procedural_scene_names(true)) EXPECT_NE(name.rfind("trap_", 0), 0u) << name;
}

// naive_first_leaf_hit on hand-made event lists.
using namespace testing::events;

TEST(NaiveFirstLeafHit, ClosestOfTheFirstLeafWithAHit) {
  using K = TraceEventKind;
  const std::vector<TraceEvent> ev = {
      event(K::Visit, 0), test_prim(1, false),                                     // no hit: go on
      event(K::Visit, 1), test_prim(2, true, 5.0f), event(K::NewClosest), test_prim(3, true, 4.0f),
      test_prim(4, true, 4.0f), test_prim(5, false),                               // stop: the leaf's last test
      event(K::Pop, 2), event(K::Visit, 2), test_prim(6, true, 1.0f), event(K::Done)};
  const NaiveAnswer a = naive_first_leaf_hit(ev);
  EXPECT_TRUE(a.hit);
  EXPECT_EQ(a.prim, 3);  // 4 ties with it at t=4: the first one counts
  EXPECT_EQ(a.t, 4.0f);
  EXPECT_EQ(a.stop_step, 7u);
  EXPECT_EQ(naive_line(a), "naive hit 3 4");
}

TEST(NaiveFirstLeafHit, CellsCountAsLeaves) {
  using K = TraceEventKind;
  const std::vector<TraceEvent> ev = {event(K::EnterCell, 0), event(K::EnterCell, 1), test_prim(7, true, 0.25f),
                                      event(K::EnterCell, 2), test_prim(8, true, 0.125f), event(K::Done)};
  const NaiveAnswer a = naive_first_leaf_hit(ev);
  EXPECT_TRUE(a.hit);
  EXPECT_EQ(a.prim, 7);
  EXPECT_EQ(a.stop_step, 2u);
}

TEST(NaiveFirstLeafHit, NoHitIsAMissStoppingAtTheLastEvent) {
  using K = TraceEventKind;
  const std::vector<TraceEvent> ev = {event(K::Visit, 0), test_prim(1, false), event(K::Done)};
  const NaiveAnswer a = naive_first_leaf_hit(ev);
  EXPECT_FALSE(a.hit);
  EXPECT_EQ(a.prim, -1);
  EXPECT_EQ(a.stop_step, 2u);
  EXPECT_EQ(naive_line(a), "naive miss");
  EXPECT_FALSE(naive_first_leaf_hit({}).hit);
}

}  // namespace
}  // namespace accel
