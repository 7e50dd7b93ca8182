// A student's false claims in the ray debugger (tools/false_claims.h): the kit's audit of a
// hand-made walk with a false early exit and a false cull, the words the viewer shows for
// them, and the debug ray auditing a student's structure (never a built-in one).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "accelviz_student.h"
#include "built_structure.h"
#include "student/kit_structure.h"
#include "student/walk_audit.h"
#include "tools/debug_ray.h"
#include "tools/false_claims.h"
#include "traps.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using accel::TraceEvent;
using accel::TraceEventKind;

// The lecture's kd-tree trap (core/traps.cpp): the ray from x = -1 along +x enters the
// scene box at t = 1 and leaves at t = 7; the root splits at x = 3 (t_split = 4). The slanted
// triangle 0 straddles the plane, stored in both leaves, and is hit at t = 5 (x = 4), in the
// far leaf; the small triangle 1, in the far leaf only, is hit at t = 4.5. The right walk
// pops the far child (t_hit 5 >= t_split 4) and answers triangle 1; the false walk below
// exits early there and skips the far child as "beyond the closest hit".
constexpr float kSplit = 3.0f;

accel::Scene trap_scene() {
  auto scene = accel::make_trap_scene("kd");
  EXPECT_TRUE(scene.ok());
  return std::move(scene.value());
}

accel::Ray trap_ray() {
  accel::Ray r;
  r.org = accel::Vec3(-1.0f, 0.0f, 0.0f);
  r.dir = accel::Vec3(1.0f, 0.0f, 0.0f);
  return r;
}

/// The kd-tree of the trap, as a student's build log would describe it.
accel::KitTree trap_tree(const accel::Scene& scene) {
  accel::KitTree tree;
  const accel::Aabb box = scene.bounds();
  accel::Aabb near_box = box, far_box = box;
  near_box.max.x = kSplit;
  far_box.min.x = kSplit;
  tree.nodes.resize(3);
  for (uint32_t id = 0; id < 3; ++id) {
    tree.nodes[id].student_id = id;
    tree.dense_of[id] = id;
  }
  accel::KitNode &root = tree.nodes[0], &near = tree.nodes[1], &far = tree.nodes[2];
  root.box = box, root.prim_count = 2, root.children = {1, 2}, root.split_axis = 0, root.split_pos = kSplit;
  near.parent = 0, near.depth = 1, near.box = near_box, near.leaf = true, near.prims = {0}, near.prim_count = 1;
  far.parent = 0, far.depth = 1, far.box = far_box, far.leaf = true, far.prims = {0, 1}, far.prim_count = 2;
  return tree;
}

TraceEvent event(TraceEventKind kind, accel::NodeId node, float t0, float t1 = 0.0f) {
  TraceEvent e;
  e.kind = kind;
  e.node = node;
  e.t0 = t0;
  e.t1 = t1;
  e.depth = node == 0 ? 0 : 1;
  return e;
}

TraceEvent tested(int32_t prim, float t) {
  TraceEvent e = event(TraceEventKind::TestPrim, accel::kNoNode, t);
  e.prim = prim;
  e.hit = true;
  return e;
}

/// The walk of the planted bug (tests/student/solutions/kdtree.cpp, PLANT_BUG_KD_FALSE_EARLY_EXIT):
/// step 5 pops the far child and claims "t_hit 5 < t_split 4: return", step 6 skips it as
/// beyond the closest hit although it is entered at t = 4.
struct FalseWalk {
  std::vector<TraceEvent> events;
  std::vector<accel::RecordedVars> vars;
  FalseWalk() {
    events = {event(TraceEventKind::Visit, 0, 1.0f, 7.0f), event(TraceEventKind::Push, 2, 4.0f),
              event(TraceEventKind::Visit, 1, 1.0f, 4.0f), tested(0, 5.0f),
              tested(0, 5.0f),  // made a NewClosest below
              event(TraceEventKind::Pop, 2, 4.0f), event(TraceEventKind::Cull, 2, 4.0f),
              event(TraceEventKind::Done, accel::kNoNode, 5.0f)};
    events[4].kind = TraceEventKind::NewClosest;
    events[6].reason = accel::CullReason::BeyondClosestHit;
    events[7].prim = 0;
    events[7].hit = true;
    accel::KdSplitVars split;
    split.t_min = 1.0f, split.t_split = 4.0f, split.t_max = 7.0f;
    split.near_child = 1, split.far_child = 2, split.axis = 0, split.kase = accel::KdCase::Both;
    accel::KdExitVars exit;
    exit.t_hit = 5.0f, exit.t_split = 4.0f, exit.far_child = 2, exit.exits = true;
    vars = {{0, split}, {5, exit}};
  }
};

TEST(FalseClaims, TheAuditFindsTheFalseEarlyExitAndTheFalseCull) {
  const accel::Scene scene = trap_scene();
  const accel::KitTree tree = trap_tree(scene);
  const accel::WalkAuditor auditor(tree, accelviz::Kind::kdtree, scene);
  const FalseWalk walk;
  const accel::WalkAudit audit = auditor.audit(trap_ray(), walk.events, walk.vars, /*find_lossy=*/true);
  ASSERT_EQ(audit.claims.size(), 2u);
  const accel::FalseClaim& exit = audit.claims[0];
  EXPECT_EQ(exit.step, 5u);
  EXPECT_EQ(exit.cause, "kd_false_early_exit");
  EXPECT_TRUE(exit.loses_hit);
  EXPECT_NE(exit.claim.find("t_hit=5 < t_split=4: return"), std::string::npos) << exit.claim;
  EXPECT_NE(exit.truth.find("triangle 1, hit at t=4.5"), std::string::npos) << exit.truth;
  const accel::FalseClaim& cull = audit.claims[1];
  EXPECT_EQ(cull.step, 6u);
  EXPECT_EQ(cull.cause, "false_cull_beyond");
  EXPECT_TRUE(cull.loses_hit);
  EXPECT_NE(cull.claim.find("node 2 skipped: entry beyond the closest hit"), std::string::npos) << cull.claim;
  EXPECT_NE(cull.truth.find("before the closest hit t=5"), std::string::npos) << cull.truth;
  EXPECT_EQ(audit.at(5), &exit);
  EXPECT_EQ(audit.at(6), &cull);
  EXPECT_EQ(audit.at(2), nullptr);
  EXPECT_EQ(audit.first_lossy(), &exit);

  // The right walk (no early exit: the far child visited, triangle 1 found) claims nothing false.
  FalseWalk right;
  right.events.resize(5);
  right.events.push_back(event(TraceEventKind::Pop, 2, 4.0f));
  right.events.push_back(event(TraceEventKind::Visit, 2, 4.0f, 7.0f));
  right.events.push_back(tested(1, 4.5f));
  right.events.push_back(event(TraceEventKind::Done, accel::kNoNode, 4.5f));
  right.events.back().prim = 1;
  right.events.back().hit = true;
  std::get<accel::KdExitVars>(right.vars[1].vars).exits = false;
  EXPECT_TRUE(auditor.audit(trap_ray(), right.events, right.vars, true).claims.empty());
}

TEST(FalseClaims, TheStepsSayFalseWithTheTruthNeverTheClaimAlone) {
  const accel::Scene scene = trap_scene();
  const accel::KitTree tree = trap_tree(scene);
  const FalseWalk walk;
  const std::optional<accel::WalkAudit> audit =
      accel::WalkAuditor(tree, accelviz::Kind::kdtree, scene).audit(trap_ray(), walk.events, walk.vars, true);

  // The cull is the claim itself: its sentence ("skip node 2 ...: entry beyond the closest
  // hit") is not repeated, the FALSE text with the truth stands instead.
  const auto at_cull = claims_at(audit, 6);
  ASSERT_EQ(at_cull.size(), 1u);
  const std::string cull = step_text(walk.events[6], at_cull);
  EXPECT_EQ(cull.rfind("FALSE: the log says \"node 2 skipped: entry beyond the closest hit", 0), 0u) << cull;
  EXPECT_NE(cull.find("; true: "), std::string::npos) << cull;
  EXPECT_EQ(cull.find(accel::describe_event(walk.events[6])), std::string::npos) << cull;
  // The pop is true as an event; its early exit is the false claim, said after it.
  const std::string pop = step_text(walk.events[5], claims_at(audit, 5));
  EXPECT_EQ(pop.rfind(accel::describe_event(walk.events[5]) + " -- FALSE: the log says \"t_hit=5 < t_split=4", 0), 0u)
      << pop;
  // Steps with no false claim read as before.
  EXPECT_EQ(step_text(walk.events[2], claims_at(audit, 2)), accel::describe_event(walk.events[2]));

  // The Variables panel shows the early exit's variables at the pop and at the cull after
  // it: their claim is the pop's.
  EXPECT_EQ(shown_vars_event(walk.events, walk.vars, 5), std::optional<size_t>(5));
  EXPECT_EQ(shown_vars_event(walk.events, walk.vars, 6), std::optional<size_t>(5));
  EXPECT_EQ(shown_vars_event(walk.events, walk.vars, 0), std::optional<size_t>(0));
  EXPECT_EQ(shown_vars_event(walk.events, walk.vars, 2), std::nullopt);  // a leaf: none shown

  // The summary counts steps from 1, as the panels and print-step do.
  EXPECT_EQ(claims_summary(*audit), "the kit found 2 false claims in this walk (first at step 6)");
  EXPECT_EQ(claims_summary(accel::WalkAudit{}), "the kit found no false claim in this walk");
  const std::vector<std::string> lines = claims_lines(audit);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("claim 6: kd_false_early_exit: t_hit=5 < t_split=4: return (node 2 skipped) -- ", 0), 0u)
      << lines[0];
  EXPECT_EQ(lines[1].rfind("claim 7: false_cull_beyond: node 2 skipped: entry beyond the closest hit", 0), 0u)
      << lines[1];
  EXPECT_EQ(claims_lines(accel::WalkAudit{}), std::vector<std::string>{"claims: none"});
  EXPECT_EQ(claims_lines(std::nullopt), std::vector<std::string>{"claims: none (a built-in structure: not audited)"});
}

/// A student's kd-tree that builds the trap's tree and logs the false walk above on any ray.
class FalseExitKd final : public accelviz::StudentStructure {
 public:
  void build(const accelviz::Scene& scene, accelviz::BuildLog& log) override {
    accelviz::Box near = scene.bounds(), far = scene.bounds();
    near.hi.x = kSplit;
    far.lo.x = kSplit;
    log.node(0, accelviz::kNoParent, 0, scene.bounds(), std::vector<uint32_t>{0, 1});
    log.split(0, 0, kSplit, 1.0f, 2.0f, 1, 2);
    log.node(1, 0, 1, near, std::vector<uint32_t>{0});
    log.leaf(1, std::vector<uint32_t>{0});
    log.node(2, 0, 1, far, std::vector<uint32_t>{0, 1});
    log.leaf(2, std::vector<uint32_t>{0, 1});
  }
  accelviz::Hit intersect(const accelviz::Ray&, accelviz::TraversalLog log) const override {
    log.visit(0, 0, 1.0f, 7.0f);
    log.kd_split(1.0f, 4.0f, 7.0f, 1, 2, 0);
    log.push(2, 1, 4.0f);
    log.visit(1, 1, 1.0f, 4.0f);
    log.triangle_tested(0, true, 5.0f);
    log.new_closest(0, 5.0f);
    log.pop(2, 1, 4.0f);
    log.kd_far_pop(5.0f, 4.0f, 2, true);
    log.cull(2, 1, accelviz::Cull::BeyondClosestHit, 4.0f);
    accelviz::Hit hit;
    hit.prim = 0;
    hit.t = 5.0f;
    return hit;
  }
};

TEST(FalseClaims, TheDebugRayAuditsAStudentsWalkOnly) {
  auto scene = std::make_shared<const accel::Scene>(trap_scene());
  accel::KitStructure kit("test_false_exit", accelviz::Kind::kdtree,
                          [] { return std::make_unique<FalseExitKd>(); });
  ASSERT_TRUE(kit.build(*scene, accel::ParamSet{}).ok());
  DebugRay ray;
  ray.active = true;
  ray.ray = trap_ray();
  ray.record(kit, false, scene.get());
  ASSERT_TRUE(ray.audit.has_value());
  ASSERT_EQ(ray.audit->claims.size(), 2u);
  EXPECT_EQ(ray.audit->claims[0].cause, "kd_false_early_exit");
  EXPECT_EQ(ray.audit->claims[1].cause, "false_cull_beyond");
  const auto& events = ray.player.events();
  ASSERT_GT(events.size(), ray.audit->claims[1].step);
  EXPECT_EQ(events[ray.audit->claims[1].step].kind, TraceEventKind::Cull);
  // Without the scene it was built over, nothing is audited.
  ray.record(kit, false);
  EXPECT_FALSE(ray.audit.has_value());

  // A built-in structure is never audited: its walk is the core's own.
  StructureRequest req;
  req.name = "kdtree";
  auto built = build_structure_now(scene, req);
  ASSERT_TRUE(built.ok()) << built.error().message;
  ray.record(*built.value()->structure, false, scene.get());
  EXPECT_FALSE(ray.audit.has_value());
  EXPECT_EQ(claims_lines(ray.audit).front(), "claims: none (a built-in structure: not audited)");
}

}  // namespace
}  // namespace viz
