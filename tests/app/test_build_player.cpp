// The construction mode's logic (tools/build_playback.h): the step player, recording with
// the depth-limit retry on a truncated trace (accel::record_within_budget, under the
// accel::build_structure_recorded the mode calls), the step line, the cost plot, what a step
// draws, the construction pseudo code, and the script commands.
#include <gtest/gtest.h>

#include <limits>

#include "pseudo_code.h"
#include "commands.h"
#include "script.h"
#include "structures/bvh_builders.h"
#include "tools/build_playback.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using accel::Aabb;
using accel::BuildEvent;
using accel::BuildEventKind;
using accel::BuildRecorder;
using accel::BuildTrace;
using accel::kNoBuildNode;
using accel::Vec3;

// Two triangles side by side along x: 0 in [0,1], 1 in [2,3].
accel::Scene two_triangles() {
  return accel::Scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}}, {{0, 1, 2}, {3, 4, 5}},
                      "two");
}

// The first recording records every depth (accel::record_within_budget's first attempt).
constexpr int kEveryDepth = std::numeric_limits<int>::max();

Aabb box(Vec3 lo, Vec3 hi) {
  Aabb b;
  b.min = lo;
  b.max = hi;
  return b;
}

TEST(BuildStepPlayer, StepsBackEndAndClamps) {
  BuildStepPlayer p;
  EXPECT_TRUE(p.empty());
  EXPECT_FALSE(p.step_forward());
  p.load(4);
  EXPECT_EQ(p.step(), 0u);
  EXPECT_EQ(p.size(), 4u);
  EXPECT_TRUE(p.step_forward());
  EXPECT_EQ(p.step(), 1u);
  EXPECT_TRUE(p.step_forward(10));  // clamped to the end: every step applied
  EXPECT_EQ(p.step(), 4u);
  EXPECT_TRUE(p.at_end());
  EXPECT_FALSE(p.step_forward());
  EXPECT_TRUE(p.step_back(2));
  EXPECT_EQ(p.step(), 2u);
  EXPECT_TRUE(p.step_back(99));
  EXPECT_EQ(p.step(), 0u);
  EXPECT_FALSE(p.step_back());
  EXPECT_TRUE(p.jump_to_end());
  EXPECT_EQ(p.step(), 4u);
  EXPECT_TRUE(p.seek(1));
  EXPECT_FALSE(p.seek(1));
  p.seek(99);
  EXPECT_EQ(p.step(), 4u);
  // Play at the end starts over; 4 steps/s for 0.6 s is two steps, the rest carried.
  p.set_speed(4.0);
  p.play();
  EXPECT_EQ(p.step(), 0u);
  EXPECT_TRUE(p.playing());
  EXPECT_TRUE(p.advance(0.6));
  EXPECT_EQ(p.step(), 2u);
  EXPECT_TRUE(p.advance(0.2));  // 0.4 carried + 0.8: one more
  EXPECT_EQ(p.step(), 3u);
  EXPECT_TRUE(p.advance(10.0));
  EXPECT_EQ(p.step(), 4u);
  EXPECT_FALSE(p.playing());  // stops at the end
  p.pause();
  EXPECT_FALSE(p.advance(1.0));
  p.set_speed(1e9);
  EXPECT_EQ(p.speed(), BuildStepPlayer::kMaxSpeed);
  p.load(0);
  p.play();
  EXPECT_FALSE(p.playing());
}

// A fake builder: a complete binary tree of depth `depth` over 2^depth triangles, node ids
// in depth-first order, as a recorded top-down build would emit it.
accel::Status fake_tree(BuildRecorder& r, int depth) {
  const Aabb b = box({0, 0, 0}, {1, 1, 1});
  r.scene_box(b);
  uint32_t next = 0;
  std::vector<uint32_t> prims;
  auto rec = [&](auto&& self, uint32_t parent, int d, uint32_t first, uint32_t count) -> void {
    const uint32_t id = next++;
    prims.resize(count);
    for (uint32_t i = 0; i < count; ++i) prims[i] = first + i;
    r.node(id, parent, d, b, b, prims.data(), count);
    if (d == depth) {
      r.leaf(id, accel::LeafReason::FewPrims, prims.data(), count);
      return;
    }
    r.split(id, 0, 0.5f, 1.0f, 2.0f, count / 2, count / 2, 0);
    self(self, id, d + 1, first, count / 2);
    self(self, id, d + 1, first + count / 2, count / 2);
  };
  rec(rec, kNoBuildNode, 0, 0, 1u << depth);
  r.done(next);
  return {};
}

TEST(RecordWithRetry, CompleteWhenTheBudgetSuffices) {
  auto rec = accel::record_within_budget([](BuildRecorder& r) { return fake_tree(r, 6); }, kEveryDepth,
                                        BuildRecorder::kDefaultBudgetBytes);
  ASSERT_TRUE(rec.ok());
  ASSERT_EQ(rec.value().attempts.size(), 1u);
  EXPECT_EQ(rec.value().attempts[0].depth_limit, std::numeric_limits<int>::max());
  EXPECT_FALSE(rec.value().trace.truncated);
  EXPECT_EQ(rec.value().trace.coverage(), "complete");
  // scene box, 127 nodes, 63 splits, 64 leaves, done
  EXPECT_EQ(rec.value().trace.events.size(), 1u + 127 + 63 + 64 + 1);
}

TEST(RecordWithRetry, HalvesTheDepthOnATruncatedTrace) {
  // Room for 60 steps: the whole tree (256 steps) does not fit; to depth 3 (scene box, 15
  // nodes + 15 splits, 16 unrecorded nodes at depth 4, done = 48 steps) it does.
  const size_t budget = 60 * sizeof(BuildEvent) + 2048 * sizeof(uint32_t);
  auto rec = accel::record_within_budget([](BuildRecorder& r) { return fake_tree(r, 6); }, kEveryDepth, budget);
  ASSERT_TRUE(rec.ok());
  const auto& a = rec.value().attempts;
  ASSERT_EQ(a.size(), 2u);
  EXPECT_TRUE(a[0].truncated);
  EXPECT_EQ(a[1].depth_limit, 3);  // 6 / 2
  EXPECT_FALSE(a[1].truncated);
  const BuildTrace& t = rec.value().trace;
  EXPECT_EQ(t.coverage(), "recorded to depth 3 of 6");
  EXPECT_EQ(t.events.size(), 48u);
  EXPECT_EQ(t.events.back().kind, BuildEventKind::Done);
}

TEST(RecordWithRetry, StopsAtDepthZero) {
  // Two steps of room: even the root level is too much; the last attempt (depth 0) is kept.
  const size_t budget = 2 * sizeof(BuildEvent) + 16;
  auto rec = accel::record_within_budget([](BuildRecorder& r) { return fake_tree(r, 4); }, kEveryDepth, budget);
  ASSERT_TRUE(rec.ok());
  const auto& a = rec.value().attempts;
  ASSERT_EQ(a.size(), 4u);  // all, 4/2 = 2, 1, 0
  EXPECT_EQ(a[1].depth_limit, 2);
  EXPECT_EQ(a[2].depth_limit, 1);
  EXPECT_EQ(a[3].depth_limit, 0);
  EXPECT_TRUE(rec.value().trace.truncated);
  EXPECT_NE(rec.value().trace.coverage().find("stopped at the step budget"), std::string::npos);
}

TEST(RecordWithRetry, ErrorsPassThrough) {
  auto rec = accel::record_within_budget([](BuildRecorder&) -> accel::Status { return accel::make_error("boom"); },
                                        kEveryDepth, BuildRecorder::kDefaultBudgetBytes);
  ASSERT_FALSE(rec.ok());
  EXPECT_EQ(rec.error().message, "boom");
}

TEST(RecordStructure, BruteForceHasFourSteps) {
  const accel::Scene scene = two_triangles();
  StructureRequest request;
  request.name = "brute";
  auto rec = test::record_build(scene, request);
  ASSERT_TRUE(rec.ok()) << rec.error().message;
  const BuildTrace& t = rec.value().trace;
  ASSERT_EQ(t.events.size(), 4u);
  EXPECT_EQ(build_step_line(t, 0), "build step 0/4: nothing built yet");
  EXPECT_EQ(build_step_line(t, 1), "build step 1/4: scene box computed");
  EXPECT_EQ(build_step_line(t, 2), "build step 2/4: node 0 (depth 0) with 2 triangles");
  EXPECT_EQ(build_step_line(t, 3), "build step 3/4: leaf node 0 with 2 triangles (max primitives)");
  EXPECT_EQ(build_step_line(t, 4), "build step 4/4: done: 1 nodes");
  EXPECT_EQ(build_step_line(t, 99), "build step 4/4: done: 1 nodes");

  // What each step draws: the scene box; the root with both triangles; the leaf; the finished one.
  accel::BuildReplay replay(t);
  replay.seek(1);
  BuildView v = build_view(t, replay, scene);
  EXPECT_EQ(v.segments.size(), 12u);  // the scene box, thick
  EXPECT_TRUE(v.triangles.empty());
  replay.seek(2);
  v = build_view(t, replay, scene);
  EXPECT_EQ(v.nodes_drawn, 1u);
  EXPECT_EQ(v.lines.size(), 24u);         // the root's box, thin
  EXPECT_EQ(v.triangles.size(), 6u);      // its two triangles
  EXPECT_EQ(v.segments.size(), 12u + 6u); // current box + triangle outlines
  replay.seek(4);
  v = build_view(t, replay, scene);
  EXPECT_EQ(v.nodes_drawn, 1u);
  EXPECT_TRUE(v.triangles.empty());
  EXPECT_EQ(replay.live_nodes(), 1u);
  EXPECT_EQ(replay.leaves(), 1u);
  EXPECT_EQ(replay.references(), 2u);
}

TEST(RecordStructure, UnknownStructureIsAnError) {
  StructureRequest request;
  request.name = "nope";
  auto rec = test::record_build(two_triangles(), request);
  ASSERT_FALSE(rec.ok());
  EXPECT_NE(rec.error().message.find("unknown structure 'nope'"), std::string::npos);
}

// A hand-made SAH step of node 0 over the two triangles: candidates on x (3) and y (2),
// then the split on x at 1.5 with leaf cost 2.
BuildTrace sah_trace() {
  BuildRecorder r;
  const Aabb b = box({0, 0, 0}, {3, 1, 0});
  const uint32_t prims[] = {0, 1};
  r.scene_box(b);
  r.node(0, kNoBuildNode, 0, b, b, prims, 2);
  r.axis(0, 0, Vec3(1, 0, 0));
  const accel::SplitCandidate x[] = {{0.5f, 3.0f, 1, 1}, {1.5f, 1.25f, 1, 1}, {2.5f, 3.0f, 1, 1}};
  r.candidates(0, 0, x, 3);
  const accel::SplitCandidate y[] = {{0.25f, 2.5f, 1, 1}, {0.75f, 2.75f, 1, 1}};
  r.candidates(0, 1, y, 2);
  r.split(0, 0, 1.5f, 1.25f, 2.0f, 1, 1, 0);
  r.node(1, 0, 1, box({0, 0, 0}, {1, 1, 0}), b, prims, 1);
  r.leaf(1, accel::LeafReason::FewPrims, prims, 1);
  r.node(2, 0, 1, box({2, 0, 0}, {3, 1, 0}), b, prims + 1, 1);
  r.leaf(2, accel::LeafReason::FewPrims, prims + 1, 1);
  r.done(3);
  return r.take();
}

TEST(CostPlot, CurvesPerAxisMinimumAndLeafCost) {
  const BuildTrace t = sah_trace();
  EXPECT_TRUE(cost_plot(t, 0).curves.empty());
  EXPECT_TRUE(cost_plot(t, 3).curves.empty());  // the Axis step: nothing evaluated yet
  CostPlot p = cost_plot(t, 4);                   // x evaluated
  ASSERT_EQ(p.curves.size(), 1u);
  EXPECT_EQ(p.node, 0u);
  EXPECT_EQ(p.curves[0].axis, 0);
  EXPECT_EQ(p.curves[0].best, 1u);
  EXPECT_FALSE(p.has_leaf_cost);
  p = cost_plot(t, 5);  // x and y
  ASSERT_EQ(p.curves.size(), 2u);
  EXPECT_EQ(p.curves[1].axis, 1);
  EXPECT_EQ(p.curves[1].best, 0u);
  EXPECT_EQ(p.best_curve, 0);
  EXPECT_FLOAT_EQ(p.min_cost, 1.25f);
  EXPECT_FLOAT_EQ(p.max_cost, 3.0f);
  p = cost_plot(t, 6);  // the split: the leaf cost is known
  ASSERT_EQ(p.curves.size(), 2u);
  EXPECT_TRUE(p.has_leaf_cost);
  EXPECT_FLOAT_EQ(p.leaf_cost, 2.0f);
  EXPECT_TRUE(cost_plot(t, 7).curves.empty());  // the next node: nothing evaluated for it
}

TEST(BuildView, PlaneOfTheBestCandidateAndOfTheSplit) {
  const BuildTrace t = sah_trace();
  const accel::Scene scene = two_triangles();
  accel::BuildReplay replay(t);
  replay.seek(4);  // candidates on x: the best plane x = 1.5 across the node's box
  BuildView v = build_view(t, replay, scene);
  ASSERT_EQ(v.triangles.size(), 6u + 6u);  // two triangles + the quad
  for (size_t i = 6; i < 12; ++i) EXPECT_FLOAT_EQ(v.triangles[i].position.x, 1.5f);
  replay.seek(5);  // candidates on y: its best at y = 0.25
  v = build_view(t, replay, scene);
  ASSERT_EQ(v.triangles.size(), 12u);
  for (size_t i = 6; i < 12; ++i) EXPECT_FLOAT_EQ(v.triangles[i].position.y, 0.25f);
  replay.seek(6);  // the split: the chosen plane
  v = build_view(t, replay, scene);
  ASSERT_EQ(v.triangles.size(), 12u);
  for (size_t i = 6; i < 12; ++i) EXPECT_FLOAT_EQ(v.triangles[i].position.x, 1.5f);
  replay.seek(8);  // leaf 1: its one triangle, no plane
  v = build_view(t, replay, scene);
  EXPECT_EQ(v.triangles.size(), 3u);
  EXPECT_EQ(v.nodes_drawn, 2u);
  replay.seek(t.events.size());
  EXPECT_EQ(replay.live_nodes(), 3u);
  EXPECT_EQ(replay.leaves(), 2u);
  EXPECT_EQ(replay.references(), 2u);
}

TEST(BuildView, GridInsertDrawsTheBboxCellsAndTheCellsKept) {
  // A 2x1x1 grid; triangle 1's bbox covers both cells, only cell 1 keeps it.
  BuildTrace t;
  BuildEvent res;
  res.kind = BuildEventKind::GridResolution;
  res.box = box({0, 0, 0}, {4, 1, 1});
  res.a = 2;
  res.b = 1;
  res.count = 1;
  t.events.push_back(res);
  BuildEvent ins;
  ins.kind = BuildEventKind::GridInsert;
  ins.prim = 1;
  ins.lo[0] = 0;
  ins.hi[0] = 1;
  ins.first = 0;
  ins.list_count = 1;
  t.lists.push_back(1);
  t.events.push_back(ins);
  const accel::Scene scene = two_triangles();
  accel::BuildReplay replay(t);
  replay.seek(2);
  const BuildView v = build_view(t, replay, scene);
  // grid box (12) + the kept cell (12) + the triangle's outline (3)
  EXPECT_EQ(v.segments.size(), 12u + 12u + 3u);
  // the filled cell (24) + both bbox cells (48)
  EXPECT_EQ(v.lines.size(), 24u + 48u);
  EXPECT_EQ(v.triangles.size(), 3u);
  EXPECT_FLOAT_EQ(v.segments[12].a.x >= 2.0f ? 1.0f : 0.0f, 1.0f);  // cell 1 spans x in [2, 4]
  EXPECT_EQ(replay.references(), 1u);
}

TEST(BuildCode, ListingsAndLines) {
  // The listing comes from the registry entry (its construction family), so every
  // registered structure has one, and an unknown name has none.
  for (const std::string& name : accel::structure_names())
    EXPECT_NE(build_code_kind(name, {}), BuildCodeKind::Unknown) << name;
  EXPECT_EQ(build_code_kind("no_such_structure", {}), BuildCodeKind::Unknown);
  using F = accel::ConstructionFamily;
  using K = accel::BvhBuilderKind;
  const BuildCodeKind brute = build_code_of(F::Linear), grid = build_code_of(F::GridInsert),
                      octree = build_code_of(F::Octree), kdtree = build_code_of(F::KdTree);
  EXPECT_EQ(build_code_kind("brute", {}), brute);
  EXPECT_EQ(build_code_kind("octree", {}), octree);
  EXPECT_EQ(build_code_kind("grid", {}), grid);
  EXPECT_EQ(build_code_kind("kdtree", {"split=middle"}), kdtree);
  EXPECT_EQ(build_code_kind("bvh", {}), build_code_of(K::BinnedSah));  // the default builder
  EXPECT_EQ(build_code_kind("bvh", {"builder=pca_sah"}), build_code_of(K::PcaSah));
  EXPECT_EQ(build_code_kind("spheretree", {"builder=insertion"}), build_code_of(K::Insertion));
  EXPECT_EQ(build_code_kind("bvh", {"builder=bottom_up"}), build_code_of(K::BottomUp));
  EXPECT_EQ(build_code_kind("bvh", {"builder=sbvh"}), build_code_of(K::Sbvh));
  // Every builder of the core's table has its label and a listing of its own.
  std::vector<BuildCodeKind> kinds = {kdtree, octree, grid, brute};
  for (const accel::BvhBuilderInfo& row : accel::bvh_builder_table()) {
    const BuildCodeKind k = build_code_of(row.kind);
    EXPECT_EQ(build_code_kind("bvh", {std::string("builder=") + row.name}), k) << row.name;
    EXPECT_STREQ(build_code_label(k), row.label);
    kinds.push_back(k);
  }
  const BuildTrace t = sah_trace();
  for (const BuildCodeKind& k : kinds) {
    const PseudoCode& code = build_pseudo_code(k);
    ASSERT_EQ(code.lines.size(), code.anchors.size());
    EXPECT_EQ(build_code_line(k, nullptr), -1);
    const int done = build_code_line(k, &t.events.back());
    ASSERT_GE(done, 0) << code.title;
    EXPECT_EQ(code.anchors[size_t(done)], "done");
  }
  const PseudoCode& kd = build_pseudo_code(kdtree);
  const int split = build_code_line(kdtree, &t.events[5]);
  ASSERT_GE(split, 0);
  EXPECT_EQ(kd.anchors[size_t(split)], "split");
  const int cands = build_code_line(build_code_of(K::Sah), &t.events[3]);
  EXPECT_EQ(build_pseudo_code(build_code_of(K::Sah)).anchors[size_t(cands)], "candidates");
  EXPECT_EQ(build_code_line(octree, &t.events[6]), build_code_line(octree, &t.events[1]));  // every Node on the build() line
}

TEST(BuildScript, ParsesTheConstructionCommands) {
  auto parsed = parse_script("construct\nbuild-step 3\nbuild-step back 2\nbuild-step end\nbuild-step start\n"
                             "print-build-step\nsah-plot off\n",
                             "t.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 7u);
  EXPECT_EQ(c[0].verb, "construct");
  EXPECT_EQ(c[1].verb, "build-step");
  EXPECT_EQ(c[1].get<PlayerMove>().mode, StepMode::Forward);
  EXPECT_EQ(c[1].get<PlayerMove>().count, 3);
  EXPECT_EQ(c[2].get<PlayerMove>().mode, StepMode::Back);
  EXPECT_EQ(c[2].get<PlayerMove>().count, 2);
  EXPECT_EQ(c[3].get<PlayerMove>().mode, StepMode::End);
  EXPECT_EQ(c[4].get<PlayerMove>().mode, StepMode::Start);
  EXPECT_EQ(c[5].verb, "print-build-step");
  EXPECT_EQ(c[6].verb, "sah-plot");
  EXPECT_FALSE(c[6].get<OnOff>().on);
  const std::pair<const char*, const char*> errors[] = {
      {"build-step\n", "t.txt:1: usage: build-step N | build-step end"},
      {"build-step -1\n", "t.txt:1: usage: build-step N"},
      {"build-step back\n", "t.txt:1: usage: build-step N"},
      {"build-step hit\n", "t.txt:1: usage: build-step N"},
      {"construct now\n", "t.txt:1: 'construct' takes no arguments"},
      {"print-build-step 2\n", "t.txt:1: 'print-build-step' takes no arguments"},
      {"sah-plot maybe\n", "t.txt:1: usage: sah-plot on|off"},
  };
  for (const auto& [text, expected] : errors) {
    auto p = parse_script(text, "t.txt");
    ASSERT_FALSE(p.ok()) << text;
    EXPECT_NE(p.error().message.find(expected), std::string::npos) << text << ": " << p.error().message;
  }
}

}  // namespace
}  // namespace viz
