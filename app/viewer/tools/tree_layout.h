#pragma once
// GL-free, ImGui-free model of the "Tree" diagram (tools/tree_diagram.h draws it): the
// hierarchy's shape (TreeShape: a built structure or the construction replay), a tidy
// top-down layout of the part worth showing, the state of every shown node at a trace
// step, the grid's cell walk as table rows, and the SAH cost of a subtree. Everything comes
// from the structure's interface and the recorded trace; nothing re-runs a traversal.
//
//   TreeShape / StructureTreeShape / ReplayTreeShape   children and per-node numbers
//   TreeIndex        parents and subtree sizes of every node (one O(n) pass per shape)
//   layout_tree()    items (nodes and collapsed subtrees) with x by leaf order, y by depth
//   TraceStates      each shown node's state at a step (per-node event lists, binary search)
//   grid_walk_rows() the grid's EnterCell steps as (X, Y, Z) rows
//   subtree_sah_cost()
#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "build_replay.h"
#include "structure.h"
#include "trace.h"

namespace viz {

using accel::NodeId;
using accel::kNoNode;

// ---------------------------------------------------------------------------------------
// The shape

/// What the diagram shows of one node.
struct TreeNodeInfo {
  bool leaf = true;
  uint32_t prims = 0;  ///< triangles of a leaf (inner nodes: 0)
  int depth = 0;
  float area = 0.0f;   ///< surface area of its box (sphere tree: of its sphere), for the SAH cost
};

/// A tree the diagram can lay out: roots, children in the structure's order, node numbers.
class TreeShape {
 public:
  virtual ~TreeShape() = default;
  /// The roots (one for a built structure; a construction may have several loose clusters).
  virtual std::vector<NodeId> roots() const = 0;
  /// The children of `id` (empty for a leaf or an unknown id).
  virtual std::vector<NodeId> children(NodeId id) const = 0;
  virtual TreeNodeInfo info(NodeId id) const = 0;
};

/// A built structure's tree through the core interface (node_children, node_view). Root 0;
/// an empty structure (no nodes) has no roots.
class StructureTreeShape final : public TreeShape {
 public:
  /// `s` must outlive the shape; `nodes` is its BuildStats::nodes (0: empty).
  StructureTreeShape(const accel::Structure& s, size_t nodes) : s_(&s), nodes_(nodes) {}
  std::vector<NodeId> roots() const override;
  std::vector<NodeId> children(NodeId id) const override { return s_->node_children(id); }
  TreeNodeInfo info(NodeId id) const override;

 private:
  const accel::Structure* s_;
  size_t nodes_;
};

/// The partly built tree of a construction step (ids are BuildReplay slots). Nodes not yet
/// split have no children; removed ("gone") nodes are left out.
class ReplayTreeShape final : public TreeShape {
 public:
  /// `replay` must outlive the shape (and not move on while it is used).
  explicit ReplayTreeShape(const accel::BuildReplay& replay);
  std::vector<NodeId> roots() const override;
  std::vector<NodeId> children(NodeId id) const override;
  TreeNodeInfo info(NodeId id) const override;

 private:
  const accel::BuildReplay* replay_;
  std::vector<int> depths_;  // from the parent links (bottom-up clusters have no recorded depth)
};

/// Parents and subtree sizes of every node reachable from the roots, from one iterative
/// pass (no recursion: kd-trees can be deep). Ids index plain vectors, so a lookup is O(1).
class TreeIndex {
 public:
  TreeIndex() = default;
  explicit TreeIndex(const TreeShape& shape);
  /// The parent of `id` (kNoNode for a root or an id never reached).
  NodeId parent(NodeId id) const { return id < parent_.size() ? parent_[id] : kNoNode; }
  /// Nodes in the subtree of `id`, itself included (0 for an id never reached).
  uint32_t subtree_nodes(NodeId id) const { return id < size_.size() ? size_[id] : 0; }
  /// Nodes reachable from the roots.
  size_t nodes() const { return reached_; }

 private:
  std::vector<NodeId> parent_;
  std::vector<uint32_t> size_;
  size_t reached_ = 0;
};

// ---------------------------------------------------------------------------------------
// The layout

/// One thing drawn: a node, or a whole subtree no event touches, collapsed into one glyph.
struct TreeItem {
  enum class Kind : uint8_t { Node, Collapsed };
  Kind kind = Kind::Node;
  NodeId node = kNoNode;      ///< the node (Collapsed: the subtree's root)
  int parent = -1;            ///< index of the parent item (-1: a root)
  int depth = 0;              ///< row, from the top (roots 0)
  float x = 0.0f;             ///< column, in leaf slots (slot k at x = k)
  bool leaf = true;           ///< a leaf node (a collapsed subtree is never one)
  uint32_t prims = 0;         ///< a leaf's triangles
  uint32_t subtree_nodes = 1; ///< nodes it stands for (itself included)
  std::vector<int> children;  ///< child items, in the structure's order
};

/// The items laid out: x by leaf order (each childless item takes the next slot, a parent
/// sits at the middle of its children), y by depth, so no two items share a place.
struct TreeLayout {
  std::vector<TreeItem> items;  ///< parents before their children (pre-order)
  int rows = 0;                 ///< deepest row + 1
  float columns = 0.0f;         ///< leaf slots used
  size_t collapsed_nodes = 0;   ///< nodes hidden inside collapsed glyphs
  std::unordered_map<NodeId, int> item_of;  ///< node -> item (collapsed subtrees by their root)
  /// The item showing `node`, or -1 (inside a collapsed glyph, or unknown).
  int find(NodeId node) const;
};

/// Which nodes to open. A node is opened (its children drawn) when it is an ancestor of a
/// focus node, or while the layout has fewer than `budget` items breadth-first from the
/// roots (the top levels, readable without a ray). Every other inner node is drawn
/// collapsed with its subtree's node count, so the layout holds O(path + siblings + budget)
/// items whatever the tree's size.
struct TreeLayoutOptions {
  std::vector<NodeId> focus;  ///< nodes the trace touches, the selection, the current build node
  std::vector<NodeId> open;   ///< nodes opened themselves too (the selection: a click opens a glyph)
  size_t budget = 31;         ///< top levels opened breadth-first while the items stay under it
};

/// Lays out `shape` (with `index` made from it) as `options` ask.
TreeLayout layout_tree(const TreeShape& shape, const TreeIndex& index, const TreeLayoutOptions& options);

/// The nodes the trace's events name (Visit, EnterCell, Cull, Push, Pop), each once.
std::vector<NodeId> touched_nodes(std::span<const accel::TraceEvent> events);

// ---------------------------------------------------------------------------------------
// The state of each node at a step

/// A node's state at the current step, in the colours of the 3D highlights.
enum class TreeNodeState : uint8_t {
  NotReached,  ///< no event has touched it yet
  OnStack,     ///< pushed and not yet popped or skipped (stack or priority queue)
  Visited,     ///< entered (or popped) before the current step
  Culled,      ///< skipped; see the reason
  Current,     ///< the node being processed (the last Visit at or before the step)
};

/// A node's state and, when culled, why and at which step.
struct TreeNodeStatus {
  TreeNodeState state = TreeNodeState::NotReached;
  accel::CullReason reason = accel::CullReason::None;
  size_t step = 0;  ///< the step of the event that set the state
};

/// The states of a trace's nodes at any step. Made once per trace (O(events)); a step's
/// state of one node is a binary search in that node's own events, so the diagram asks
/// only for the items it shows and never rescans the whole trace per frame.
class TraceStates {
 public:
  TraceStates() = default;
  explicit TraceStates(std::span<const accel::TraceEvent> events);
  /// The state of `node` after events[0..step].
  TreeNodeStatus at(NodeId node, size_t step) const;
  /// The node being processed at `step` (kNoNode before the first Visit / EnterCell).
  NodeId current(size_t step) const;
  bool empty() const { return steps_ == 0; }

 private:
  struct NodeEvent {
    size_t step;
    accel::TraceEventKind kind;
    accel::CullReason reason;
  };
  std::unordered_map<NodeId, std::vector<NodeEvent>> per_node_;
  std::vector<NodeId> current_;  // current_[s] = the node being processed after step s
  size_t steps_ = 0;
};

/// The construction's states: built nodes (leaves, split inner nodes) count as visited, a
/// node not yet split as waiting (OnStack), `current_slot` (the step's node) as current.
TreeNodeStatus replay_state(const accel::BuildReplay& replay, NodeId slot, NodeId current_slot);

// ---------------------------------------------------------------------------------------
// The grid: the cell walk as a table

/// One EnterCell step: the cell and the axis the DDA stepped on to reach it.
struct GridWalkRow {
  size_t step = 0;      ///< index of the EnterCell event
  NodeId cell = kNoNode;
  int xyz[3] = {-1, -1, -1};  ///< (X, Y, Z); -1 when neither vars nor a resolution are known
  int stepped_axis = -1;      ///< 0..2: the axis of the step into this cell; -1: the first cell
  float t0 = 0.0f, t1 = 0.0f; ///< the ray's interval inside the cell
};

/// The rows of a grid trace: (X, Y, Z) from the recorded DDA variables (GridDdaVars) when
/// there, else decoded from the linear index with `res` (x fastest; all 0: unknown).
std::vector<GridWalkRow> grid_walk_rows(std::span<const accel::TraceEvent> events,
                                        std::span<const accel::RecordedVars> vars, const int res[3]);
/// The row of the cell current at `step` (the last EnterCell at or before it), or -1.
int grid_current_row(const std::vector<GridWalkRow>& rows, size_t step);

// ---------------------------------------------------------------------------------------
// The SAH cost of a subtree

/// The SAH cost constants: ct per inner-node traversal, ci per ray/triangle test.
struct SahConstants {
  double ct = 1.0;
  double ci = 1.0;
};

/// The expected cost of tracing a ray through the subtree of `node`, given that it hits the
/// node's bounds (MacDonald & Booth 1990; Wald's SAH notes): a leaf costs ci * triangles,
/// an inner node ct + sum over its children of A(child) / A(node) * cost(child). Areas are
/// TreeNodeInfo::area; a node of zero area passes its children's costs on unweighted (a
/// flat node is hit with its children). Iterative, O(subtree). The root's value equals
/// BuildStats::sah_cost when the structure's leaves cost ci per triangle (the binary BVH, the
/// kd-tree; the wide BVH's statistic counts one leaf test per 4 triangles, so it is lower).
double subtree_sah_cost(const TreeShape& shape, NodeId node, const SahConstants& k);

/// The numbers of a subtree shown for the selected node, from one pass over it.
struct SubtreeSummary {
  double sah_cost = 0.0;     ///< subtree_sah_cost()
  size_t nodes = 0;          ///< itself included
  size_t leaves = 0;
  size_t prim_refs = 0;      ///< triangle references in its leaves
  int max_depth = 0;         ///< deepest leaf below it, relative to it (0: a leaf)
};
SubtreeSummary summarize_subtree(const TreeShape& shape, NodeId node, const SahConstants& k);

}  // namespace viz
