// The tree diagram's model (tools/tree_layout.h): node states against the trace, collapsed
// subtrees and their counts, a layout without overlaps, the grid's cell-walk rows and the
// subtree SAH cost, on hand-built trees and traces and on a real BVH.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "built_structure.h"
#include "registry.h"
#include "tools/build_playback.h"
#include "tools/debug_ray.h"
#include "tools/tree_layout.h"
#include "trace_player.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using accel::CullReason;
using accel::TraceEvent;
using accel::TraceEventKind;

/// A tree written out by hand: children and numbers per id.
class HandTree final : public TreeShape {
 public:
  struct Node {
    std::vector<NodeId> children;
    uint32_t prims = 0;
    float area = 1.0f;
  };
  std::map<NodeId, Node> nodes;
  std::vector<NodeId> roots() const override { return nodes.empty() ? std::vector<NodeId>{} : std::vector<NodeId>{0}; }
  std::vector<NodeId> children(NodeId id) const override {
    const auto it = nodes.find(id);
    return it == nodes.end() ? std::vector<NodeId>{} : it->second.children;
  }
  TreeNodeInfo info(NodeId id) const override {
    TreeNodeInfo i;
    const auto it = nodes.find(id);
    if (it == nodes.end()) return i;
    i.leaf = it->second.children.empty();
    i.prims = it->second.prims;
    i.area = it->second.area;
    return i;
  }
};

// small_tree(), children listed left to right:
//   0: 1 2 9      1: 3 4      2: 5 6      5: 7 8      9: 10 11
//   leaves 3 4 6 7 8 10 11
HandTree small_tree() {
  HandTree t;
  t.nodes[0] = {{1, 2, 9}, 0, 10.0f};
  t.nodes[1] = {{3, 4}, 0, 6.0f};
  t.nodes[2] = {{5, 6}, 0, 5.0f};
  t.nodes[3] = {{}, 2, 2.0f};
  t.nodes[4] = {{}, 1, 3.0f};
  t.nodes[5] = {{7, 8}, 0, 3.0f};
  t.nodes[6] = {{}, 4, 1.0f};
  t.nodes[7] = {{}, 1, 1.0f};
  t.nodes[8] = {{}, 1, 1.0f};
  t.nodes[9] = {{10, 11}, 0, 4.0f};
  t.nodes[10] = {{}, 3, 1.0f};
  t.nodes[11] = {{}, 5, 1.0f};
  return t;
}

TraceEvent ev(TraceEventKind k, NodeId n, CullReason why = CullReason::None) {
  TraceEvent e;
  e.kind = k;
  e.node = n;
  e.reason = why;
  return e;
}

/// A stack traversal of small_tree(): 2 waits on the stack while 1 is searched, then is
/// skipped as beyond the hit; 9 is never named (as a kd-tree's far child in case (b)).
std::vector<TraceEvent> small_trace() {
  return {
      ev(TraceEventKind::Visit, 0),                                 // 0
      ev(TraceEventKind::Push, 2),                                  // 1
      ev(TraceEventKind::Visit, 1),                                 // 2
      ev(TraceEventKind::Cull, 3, CullReason::MissedBounds),        // 3
      ev(TraceEventKind::Visit, 4),                                 // 4
      ev(TraceEventKind::TestPrim, accel::kNoNode),                 // 5
      ev(TraceEventKind::NewClosest, accel::kNoNode),               // 6
      ev(TraceEventKind::Pop, 2),                                   // 7
      ev(TraceEventKind::Cull, 2, CullReason::BeyondClosestHit),    // 8
      ev(TraceEventKind::Done, accel::kNoNode),                     // 9
  };
}

/// No two items in one row closer than one slot, every parent above its children.
void expect_no_overlaps(const TreeLayout& l) {
  std::map<int, std::vector<float>> rows;
  for (const TreeItem& it : l.items) rows[it.depth].push_back(it.x);
  for (auto& [depth, xs] : rows) {
    std::sort(xs.begin(), xs.end());
    for (size_t i = 1; i < xs.size(); ++i) EXPECT_GE(xs[i] - xs[i - 1], 1.0f - 1e-6f) << "row " << depth;
  }
  for (const TreeItem& it : l.items)
    for (int c : it.children) EXPECT_EQ(l.items[static_cast<size_t>(c)].depth, it.depth + 1);
}

TEST(TreeLayout, StatesFollowTheTrace) {
  const std::vector<TraceEvent> events = small_trace();
  const TraceStates states(events);
  // Step 4: the root and 1 visited, 4 current, 3 culled (missed), 2 on the stack.
  EXPECT_EQ(states.at(0, 4).state, TreeNodeState::Visited);
  EXPECT_EQ(states.at(1, 4).state, TreeNodeState::Visited);
  EXPECT_EQ(states.at(4, 4).state, TreeNodeState::Current);
  EXPECT_EQ(states.at(3, 4).state, TreeNodeState::Culled);
  EXPECT_EQ(states.at(3, 4).reason, CullReason::MissedBounds);
  EXPECT_EQ(states.at(3, 4).step, 3u);
  EXPECT_EQ(states.at(2, 4).state, TreeNodeState::OnStack);
  EXPECT_EQ(states.at(9, 4).state, TreeNodeState::NotReached);
  EXPECT_EQ(states.current(4), 4u);
  // Step 0: only the root, current; the rest not reached yet.
  EXPECT_EQ(states.at(0, 0).state, TreeNodeState::Current);
  for (NodeId n : {1u, 2u, 3u, 4u}) EXPECT_EQ(states.at(n, 0).state, TreeNodeState::NotReached) << n;
  // Step 7: 2 popped (off the stack); step 8: skipped beyond the closest hit.
  EXPECT_EQ(states.at(2, 7).state, TreeNodeState::Visited);
  EXPECT_EQ(states.at(2, 8).state, TreeNodeState::Culled);
  EXPECT_EQ(states.at(2, 8).reason, CullReason::BeyondClosestHit);
  EXPECT_EQ(states.at(4, 9).state, TreeNodeState::Current);  // the last node visited stays current
  EXPECT_TRUE(TraceStates().empty());
}

TEST(TreeLayout, UntouchedSubtreesCollapseWithTheirCount) {
  const HandTree tree = small_tree();
  const TreeIndex index(tree);
  EXPECT_EQ(index.nodes(), 12u);
  EXPECT_EQ(index.subtree_nodes(0), 12u);
  EXPECT_EQ(index.subtree_nodes(2), 5u);
  EXPECT_EQ(index.subtree_nodes(9), 3u);
  EXPECT_EQ(index.parent(7), 5u);
  EXPECT_EQ(index.parent(0), accel::kNoNode);

  TreeLayoutOptions options;
  options.focus = touched_nodes(small_trace());
  EXPECT_EQ(options.focus, (std::vector<NodeId>{0, 2, 1, 3, 4}));
  options.budget = 0;  // only the ray's path
  const TreeLayout l = layout_tree(tree, index, options);
  // 0 and 1 are opened (ancestors of touched nodes); 2 is touched but closed; 9 collapsed.
  ASSERT_EQ(l.items.size(), 6u);
  const int nine = l.find(9);
  ASSERT_GE(nine, 0);
  EXPECT_EQ(l.items[static_cast<size_t>(nine)].kind, TreeItem::Kind::Collapsed);
  EXPECT_EQ(l.items[static_cast<size_t>(nine)].subtree_nodes, 3u);
  const int two = l.find(2);
  ASSERT_GE(two, 0);
  EXPECT_EQ(l.items[static_cast<size_t>(two)].kind, TreeItem::Kind::Node);
  EXPECT_EQ(l.items[static_cast<size_t>(two)].subtree_nodes, 5u);
  EXPECT_TRUE(l.items[static_cast<size_t>(two)].children.empty());
  EXPECT_EQ(l.find(10), -1);  // inside the glyph
  EXPECT_EQ(l.find(5), -1);
  EXPECT_EQ(l.collapsed_nodes, 3u);
  const int four = l.find(4);
  ASSERT_GE(four, 0);
  EXPECT_TRUE(l.items[static_cast<size_t>(four)].leaf);
  EXPECT_EQ(l.items[static_cast<size_t>(four)].prims, 1u);
  EXPECT_EQ(l.rows, 3);
  expect_no_overlaps(l);
  // The root sits over the middle of its children.
  const TreeItem& root = l.items[0];
  EXPECT_EQ(root.node, 0u);
  EXPECT_FLOAT_EQ(root.x, 0.5f * (l.items[static_cast<size_t>(root.children.front())].x +
                                  l.items[static_cast<size_t>(root.children.back())].x));

  // Without a trace a budget opens the top levels breadth-first: the whole small tree.
  TreeLayoutOptions all;
  all.budget = 100;
  const TreeLayout full = layout_tree(tree, index, all);
  EXPECT_EQ(full.items.size(), 12u);
  EXPECT_EQ(full.collapsed_nodes, 0u);
  EXPECT_FLOAT_EQ(full.columns, 7.0f);  // seven leaves
  expect_no_overlaps(full);
}

TEST(TreeLayout, SahCostOfALeafAndATwoLeafTree) {
  HandTree t;
  t.nodes[0] = {{1, 2}, 0, 10.0f};
  t.nodes[1] = {{}, 2, 4.0f};
  t.nodes[2] = {{}, 3, 6.0f};
  const SahConstants k{1.0, 2.0};
  EXPECT_DOUBLE_EQ(subtree_sah_cost(t, 2, k), 6.0);  // ci * 3
  // ct + 4/10 * (2 * 2) + 6/10 * (2 * 3) = 1 + 1.6 + 3.6
  EXPECT_NEAR(subtree_sah_cost(t, 0, k), 6.2, 1e-12);
}

TEST(TreeLayout, RealBvhAgreesWithTheTraceAndItsStats) {
  auto scene = test::scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"width=2", "traversal=pqueue", "leaf_size=2"};
  auto built = build_structure_now(scene, req);
  ASSERT_TRUE(built.ok()) << built.error().message;
  const accel::Structure& s = *built.value()->structure;
  const StructureTreeShape shape(s, built.value()->stats.nodes);
  const TreeIndex index(shape);
  EXPECT_EQ(index.nodes(), built.value()->stats.nodes);

  DebugRay ray;
  ray.active = true;
  ray.ray = test::sphere_ray();
  ray.record(s, false);
  const std::vector<TraceEvent>& events = ray.player.events();
  ASSERT_GT(events.size(), 5u);
  const TraceStates states(events);
  // At every step the states agree with the player's own highlight of that step.
  for (size_t step = 0; step < events.size(); step += 3) {
    const accel::TraceHighlight h = accel::trace_highlight(events, step);
    if (h.node != accel::kNoNode) {
      EXPECT_EQ(states.at(h.node, step).state, TreeNodeState::Current) << step;
    }
    for (const accel::PendingNode& p : h.pending) EXPECT_EQ(states.at(p.node, step).state, TreeNodeState::OnStack);
    for (const accel::CulledNode& c : h.culled) {
      const TreeNodeStatus st = states.at(c.node, step);
      if (st.step == c.step) {  // not touched again since
        EXPECT_EQ(st.state, TreeNodeState::Culled);
        EXPECT_EQ(st.reason, c.reason);
      }
    }
  }
  TreeLayoutOptions options;
  options.focus = touched_nodes(events);
  const TreeLayout l = layout_tree(shape, index, options);
  for (NodeId n : options.focus) EXPECT_GE(l.find(n), 0) << n;
  EXPECT_LT(l.items.size(), index.nodes());  // the rest collapsed
  size_t shown = 0;
  for (const TreeItem& it : l.items) shown += it.kind == TreeItem::Kind::Collapsed ? it.subtree_nodes : 0;
  EXPECT_EQ(shown, l.collapsed_nodes);
  expect_no_overlaps(l);

  // The root's subtree cost is the structure's SAH cost: the binary BVH's leaves cost ci per
  // triangle (the wide one counts a test per 4 triangles, so its statistic is lower).
  const accel::BuildStats& st = built.value()->stats;
  const double root = subtree_sah_cost(shape, 0, {st.sah_ct, st.sah_ci});
  EXPECT_NEAR(root, st.sah_cost, 1e-4 * st.sah_cost);
}

TEST(TreeLayout, ConstructionShowsTheNodesBuiltSoFar) {
  auto scene = test::scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"width=2"};
  auto rec = test::record_build(*scene, req);
  ASSERT_TRUE(rec.ok()) << rec.error().message;
  accel::BuildReplay replay(rec.value().trace);
  // Part way: the nodes built so far, the step's node current and in the layout.
  replay.seek(replay.steps() / 3);
  {
    const ReplayTreeShape shape(replay);
    const TreeIndex index(shape);
    EXPECT_EQ(index.nodes(), replay.live_nodes());
    const NodeId current = replay.current() ? replay.slot(build_event_node(*replay.current())) : kNoNode;
    size_t built_nodes = 0;
    for (size_t slot = 0; slot < replay.nodes().size(); ++slot) {
      const TreeNodeStatus st = replay_state(replay, static_cast<NodeId>(slot), current);
      built_nodes += st.state == TreeNodeState::Visited;
      if (slot == current) {
        EXPECT_EQ(st.state, TreeNodeState::Current);
      }
    }
    EXPECT_GT(built_nodes, 0u);
    TreeLayoutOptions options;
    if (current != kNoNode) options.focus = {current};
    const TreeLayout l = layout_tree(shape, index, options);
    if (current != kNoNode) {
      EXPECT_GE(l.find(current), 0);
    }
    expect_no_overlaps(l);
  }
  // The end: the finished tree, every node of the built structure.
  replay.seek(replay.steps());
  const ReplayTreeShape shape(replay);
  auto built = build_structure_now(scene, req);
  ASSERT_TRUE(built.ok());
  EXPECT_EQ(TreeIndex(shape).nodes(), built.value()->stats.nodes);
}

TEST(TreeLayout, GridWalkRows) {
  // Three cells of a 4x4x4 grid stepped x then z; the middle one carries recorded DDA vars.
  std::vector<TraceEvent> events = {ev(TraceEventKind::EnterCell, 0), ev(TraceEventKind::TestPrim, accel::kNoNode),
                                    ev(TraceEventKind::EnterCell, 1), ev(TraceEventKind::EnterCell, 1 + 16)};
  accel::GridDdaVars dda;
  dda.cell[0] = 1;
  std::vector<accel::RecordedVars> vars = {{2, dda}};
  const int res[3] = {4, 4, 4};
  const std::vector<GridWalkRow> rows = grid_walk_rows(events, vars, res);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].stepped_axis, -1);
  EXPECT_EQ(rows[1].xyz[0], 1);
  EXPECT_EQ(rows[1].stepped_axis, 0);
  EXPECT_EQ(rows[2].xyz[0], 1);
  EXPECT_EQ(rows[2].xyz[2], 1);
  EXPECT_EQ(rows[2].stepped_axis, 2);
  EXPECT_EQ(grid_current_row(rows, 1), 0);
  EXPECT_EQ(grid_current_row(rows, 2), 1);
  EXPECT_EQ(grid_current_row(rows, 9), 2);
  const int unknown[3] = {0, 0, 0};
  EXPECT_EQ(grid_walk_rows(events, {}, unknown)[2].xyz[0], -1);
}

}  // namespace
}  // namespace viz
