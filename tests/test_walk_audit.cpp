// The kit's reading of a student's walk (core/student/walk_audit.h): the causes' words are
// the docs' words, and the audit reads a kd-tree walk's claims against the geometry.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "student/kit_structure.h"
#include "student/walk_audit.h"

namespace accel {
namespace {

TEST(WalkAudit, CauseTitlesAreTheDocsTable) {
  std::ifstream in(std::string(ACCEL_SOURCE_DIR) + "/docs/student.md");
  ASSERT_TRUE(in) << "docs/student.md not found";
  std::stringstream text;
  text << in.rdbuf();
  for (const CauseInfo& c : cause_table()) {
    const std::string row = std::string("| `") + c.id + "` | " + c.title + " | " + c.lecture + " |";
    EXPECT_NE(text.str().find(row), std::string::npos) << "docs/student.md lacks the row:\n" << row;
  }
}

/// A kd-tree of one split at x = 0: node 0 (the root, [-1, 1]^3), its children 1 (x < 0) and
/// 2 (x > 0), leaves; triangle 0 in the lower child, at x = -0.5 facing +x.
struct OneSplit {
  Scene scene{{{-0.5f, -0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f}, {-0.5f, 0.0f, 0.5f}}, {{0, 1, 2}}, "one"};
  KitTree tree;
  OneSplit() {
    auto node = [&](uint32_t parent, Vec3 lo, Vec3 hi) {
      KitNode k;
      k.student_id = uint32_t(tree.nodes.size());
      k.parent = parent;
      k.box.min = lo, k.box.max = hi;
      if (parent != kNoBuildNode) tree.nodes[parent].children.push_back(k.student_id);
      tree.dense_of[k.student_id] = k.student_id;
      tree.nodes.push_back(k);
    };
    node(kNoBuildNode, Vec3(-1), Vec3(1));
    node(0, Vec3(-1), Vec3(0, 1, 1));
    node(0, Vec3(0, -1, -1), Vec3(1));
    tree.nodes[0].split_axis = 0, tree.nodes[0].split_pos = 0.0f;
    tree.nodes[1].leaf = true, tree.nodes[1].prims = {0};
    tree.nodes[2].leaf = true;
  }
};

TEST(WalkAudit, PlaneBehindTheOriginIsNamed) {
  OneSplit s;
  // From x = -0.2 running -x: the plane x = 0 lies behind the origin (t_split = -0.2); the
  // ray stays in node 1 and hits triangle 0 at x = -0.5 (t = 0.3).
  Ray ray;
  ray.org = Vec3(-0.2f, 0.0f, 0.0f);
  ray.dir = Vec3(-1.0f, 0.0f, 0.0f);
  // The slide's walk: near = the child holding the origin (1), t_split = 0.2 / -1 = -0.2 <
  // t_min = 0: case (c), far only: node 2 visited, node 1 culled.
  std::vector<TraceEvent> events;
  std::vector<RecordedVars> vars;
  auto ev = [&](TraceEventKind k, NodeId n, float t0, float t1, CullReason why = CullReason::None) {
    TraceEvent e;
    e.kind = k, e.node = n, e.t0 = t0, e.t1 = t1, e.reason = why;
    events.push_back(e);
  };
  ev(TraceEventKind::Visit, 0, 0.0f, 0.8f);
  KdSplitVars kd;
  kd.t_min = 0.0f, kd.t_split = -0.2f, kd.t_max = 0.8f, kd.near_child = 1, kd.far_child = 2, kd.kase = KdCase::FarOnly;
  vars.push_back({0, kd});
  ev(TraceEventKind::Cull, 1, -0.2f, -0.2f, CullReason::MissedBounds);
  ev(TraceEventKind::Visit, 2, 0.0f, 0.8f);
  TraceEvent done;
  done.kind = TraceEventKind::Done;
  events.push_back(done);

  const WalkAuditor auditor(s.tree, accelviz::Kind::kdtree, s.scene);
  const WalkAudit audit = auditor.audit(ray, events, vars, true);
  ASSERT_NE(audit.first_lossy(), nullptr);
  EXPECT_EQ(audit.first_lossy()->cause, "kd_plane_behind_origin");
  EXPECT_EQ(audit.first_lossy()->step, 0u);
  EXPECT_EQ(audit.visits_not_crossed, 1u);  // node 2: the ray never enters it
  const Diagnosis d = auditor.diagnose(ray, events, vars, audit, Hit{}, ReferenceHit{0, 0.3});
  EXPECT_EQ(d.cause, "kd_plane_behind_origin");
  EXPECT_NE(d.detail.find("triangle 0"), std::string::npos) << d.detail;
}

}  // namespace
}  // namespace accel
