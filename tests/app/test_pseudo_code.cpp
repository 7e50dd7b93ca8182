// The pseudo-code mapping of real traces: every event of every traversal has a line.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "built_structure.h"
#include "pseudo_code.h"
#include "registry.h"
#include "structures/bvh_builders.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using test::scene_of;
using test::sphere_ray;

// ---------------------------------------------------------------------------------------
// Pseudo code: every event of every real traversal maps to a line

TEST(PseudoCode, EveryEventOfEveryTraversalHasALine) {
  auto scene = scene_of("cornell");
  std::vector<accel::Ray> rays = accel::random_rays(scene->bounds(), 24, 7);
  rays.push_back(sphere_ray());
  accel::Ray miss;
  miss.org = glm::vec3(10.0f, 10.0f, 10.0f);
  miss.dir = glm::vec3(0.0f, 1.0f, 0.0f);
  rays.push_back(miss);
  for (const auto& info : accel::structure_registry()) {
    std::vector<std::string> traversals = {""};
    for (const auto& spec : info.params)
      if (spec.name == "traversal") traversals = spec.choices;
    for (const std::string& t : traversals) {
      StructureRequest req;
      req.name = info.name;
      if (!t.empty()) req.params = {"traversal=" + t};
      auto built = build_structure_now(scene, req);
      ASSERT_TRUE(built.ok()) << built.error().message;
      const BuiltStructure& b = *built.value();
      ASSERT_NE(b.kind, TraversalKind::Unknown) << info.name;
      const PseudoCode& code = pseudo_code(b.kind);
      ASSERT_EQ(code.lines.size(), code.anchors.size());
      std::set<std::string> anchors_seen;
      for (const accel::Ray& ray : rays) {
        accel::TraceRecorder rec;
        b.structure->intersect_traced(ray, rec);
        const NodeLookup lookup = [&b](accel::NodeId id) { return b.structure->node_view(id); };
        for (size_t i = 0; i < rec.events().size(); ++i) {
          const int line = pseudo_code_line(b.kind, rec.events(), i, lookup);
          EXPECT_GE(line, 0) << info.name << " " << t << ": " << accel::describe_event(rec.events()[i]);
          if (line >= 0) anchors_seen.insert(code.anchors[size_t(line)]);
        }
      }
      // The loop's core lines are reached.
      EXPECT_TRUE(anchors_seen.count("test")) << info.name << " " << t;
      EXPECT_TRUE(anchors_seen.count("closest")) << info.name << " " << t;
    }
  }
}

TEST(PseudoCode, KdTreeCasesAndGridAxes) {
  using accel::TraceEvent;
  using accel::TraceEventKind;
  auto ev = [](TraceEventKind k, accel::NodeId n, float t0, float t1) {
    TraceEvent e;
    e.kind = k;
    e.node = n;
    e.t0 = t0;
    e.t1 = t1;
    return e;
  };
  // Visit [1, 2]; skipped child with t_split 3 > t_max: case (b); t_split 0.5 < t_min: (c).
  std::vector<TraceEvent> b = {ev(TraceEventKind::Visit, 0, 1, 2), ev(TraceEventKind::Cull, 2, 3, 3)};
  std::vector<TraceEvent> c = {ev(TraceEventKind::Visit, 0, 1, 2), ev(TraceEventKind::Cull, 1, 0.5f, 0.5f)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, b, 1, {}), "case_b");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, c, 1, {}), "case_c");
  std::vector<TraceEvent> a = {ev(TraceEventKind::Visit, 0, 1, 2), ev(TraceEventKind::Push, 2, 1.5f, 1.5f)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, a, 1, {}), "case_a");
  std::vector<TraceEvent> root_miss = {ev(TraceEventKind::Cull, 0, 0, 0)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, root_miss, 0, {}), "root");

  // Grid: the axis stepped between two cells, from their boxes.
  auto cell = [](accel::NodeId id) {
    accel::NodeView v;
    v.id = id;
    const int x = int(id % 4), y = int(id / 4 % 4), z = int(id / 16);
    v.box.min = glm::vec3(float(x), float(y), float(z));
    v.box.max = v.box.min + glm::vec3(1.0f);
    return v;
  };
  std::vector<TraceEvent> walk = {ev(TraceEventKind::EnterCell, 0, 0, 1), ev(TraceEventKind::EnterCell, 1, 1, 2),
                                  ev(TraceEventKind::EnterCell, 5, 2, 3), ev(TraceEventKind::EnterCell, 21, 3, 4)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 0, cell), "enter_first");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 1, cell), "step_x");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 2, cell), "step_y");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 3, cell), "step_z");
  EXPECT_EQ(traversal_kind(accel::TraversalFamily::Hierarchy, "pqueue"), TraversalKind::HierarchyPqueue);
  EXPECT_EQ(traversal_kind(accel::TraversalFamily::Hierarchy, ""), TraversalKind::HierarchyOrdered);
  EXPECT_EQ(traversal_kind(accel::TraversalFamily::Dda, ""), TraversalKind::Grid);
  // Every registered structure has pseudo code: its kind comes from the registry's family.
  for (const accel::StructureInfo& info : accel::structure_registry())
    EXPECT_NE(traversal_kind(info.traversal, ""), TraversalKind::Unknown) << info.name;
}

}  // namespace
}  // namespace viz

// Every row of the builders' table shows its own listing, beside the row in the core: the
// title and lines it gives, inside the one recursion's lines when it is top-down, and the
// anchors the construction's steps map to.
TEST(PseudoCode, EveryBvhBuilderShowsTheListingBesideItsRow) {
  for (const accel::BvhBuilderInfo& row : accel::bvh_builder_table()) {
    ASSERT_NE(row.listing, nullptr) << row.name;
    const viz::PseudoCode& code = viz::build_pseudo_code(viz::build_code_of(row.kind));
    EXPECT_EQ(code.title, row.listing->title) << row.name;
    for (const accel::ListingLine& line : row.listing->lines) {
      EXPECT_NE(std::find(code.lines.begin(), code.lines.end(), line.text), code.lines.end()) << row.name;
    }
    for (const char* anchor : {"scene_box", "node", "leaf", "fit", "done"}) {
      EXPECT_NE(std::find(code.anchors.begin(), code.anchors.end(), anchor), code.anchors.end())
          << row.name << ": " << anchor;
    }
    if (row.top_down) {
      EXPECT_NE(std::find(code.lines.begin(), code.lines.end(), "    build(left); build(right)"), code.lines.end())
          << row.name;
    }
  }
}
