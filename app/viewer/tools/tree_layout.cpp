// The tree diagram's model: shapes, the index, the layout, the states, the grid rows and
// the subtree SAH cost (tree_layout.h). GL-free; tests/app/test_tree_layout.cpp drives it.
#include "tools/tree_layout.h"

#include <algorithm>
#include <numbers>
#include <unordered_set>

namespace viz {
namespace {

float node_area(const accel::NodeView& v) {
  if (!v.sphere.empty()) return 4.0f * std::numbers::pi_v<float> * v.sphere.radius * v.sphere.radius;
  return v.box.empty() ? 0.0f : v.box.area();
}

bool names_node(accel::TraceEventKind k) {
  using K = accel::TraceEventKind;
  return k == K::Visit || k == K::EnterCell || k == K::Cull || k == K::Push || k == K::Pop;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Shapes

std::vector<NodeId> StructureTreeShape::roots() const {
  if (nodes_ == 0) return {};
  return {0};  // every hierarchy in core/structures stores its root at index 0
}

TreeNodeInfo StructureTreeShape::info(NodeId id) const {
  const accel::NodeView v = s_->node_view(id);
  TreeNodeInfo out;
  out.leaf = v.leaf;
  out.prims = v.leaf ? v.prim_count : 0;
  out.depth = v.depth;
  out.area = node_area(v);
  return out;
}

ReplayTreeShape::ReplayTreeShape(const accel::BuildReplay& replay) : replay_(&replay), depths_(replay.depths()) {}

std::vector<NodeId> ReplayTreeShape::roots() const {
  std::vector<NodeId> out;
  const auto& nodes = replay_->nodes();
  for (size_t i = 0; i < nodes.size(); ++i)
    if (!nodes[i].gone && nodes[i].parent == accel::kNoBuildNode) out.push_back(static_cast<NodeId>(i));
  return out;
}

std::vector<NodeId> ReplayTreeShape::children(NodeId id) const {
  const auto& nodes = replay_->nodes();
  if (id >= nodes.size() || nodes[id].gone) return {};
  std::vector<NodeId> out;
  for (uint32_t c : nodes[id].children)
    if (c < nodes.size() && !nodes[c].gone) out.push_back(c);
  return out;
}

TreeNodeInfo ReplayTreeShape::info(NodeId id) const {
  TreeNodeInfo out;
  const auto& nodes = replay_->nodes();
  if (id >= nodes.size()) return out;
  const accel::ReplayNode& n = nodes[id];
  // A node not yet split has no children but is no leaf yet: drawn as a leaf-to-be.
  out.leaf = n.leaf || n.children.empty();
  out.prims = n.prim_count;
  out.depth = id < depths_.size() && depths_[id] >= 0 ? depths_[id] : n.depth;
  out.area = !n.sphere.empty() ? 4.0f * std::numbers::pi_v<float> * n.sphere.radius * n.sphere.radius
             : n.box.empty()   ? 0.0f
                               : n.box.area();
  return out;
}

// ---------------------------------------------------------------------------------------
// The index

TreeIndex::TreeIndex(const TreeShape& shape) {
  // Pre-order by an explicit stack; sizes accumulate in reverse pre-order, where every
  // node comes after all of its descendants.
  std::vector<NodeId> order;
  std::vector<NodeId> stack = shape.roots();
  auto grow = [&](NodeId id) {
    if (id >= parent_.size()) {
      const size_t n = std::max<size_t>(size_t(id) + 1, parent_.size() * 2);
      parent_.resize(n, kNoNode);
      size_.resize(n, 0);
    }
  };
  for (NodeId r : stack) grow(r);
  while (!stack.empty()) {
    const NodeId n = stack.back();
    stack.pop_back();
    if (size_[n] != 0) continue;  // reached twice: a malformed shape, keep the first parent
    size_[n] = 1;
    order.push_back(n);
    for (NodeId c : shape.children(n)) {
      grow(c);
      if (size_[c] != 0) continue;
      parent_[c] = n;
      stack.push_back(c);
    }
  }
  for (size_t i = order.size(); i-- > 0;) {
    const NodeId n = order[i];
    if (parent_[n] != kNoNode) size_[parent_[n]] += size_[n];
  }
  reached_ = order.size();
}

// ---------------------------------------------------------------------------------------
// The layout

int TreeLayout::find(NodeId node) const {
  const auto it = item_of.find(node);
  return it == item_of.end() ? -1 : it->second;
}

std::vector<NodeId> touched_nodes(std::span<const accel::TraceEvent> events) {
  std::unordered_set<NodeId> seen;
  std::vector<NodeId> out;
  for (const accel::TraceEvent& e : events)
    if (names_node(e.kind) && e.node != kNoNode && seen.insert(e.node).second) out.push_back(e.node);
  return out;
}

TreeLayout layout_tree(const TreeShape& shape, const TreeIndex& index, const TreeLayoutOptions& options) {
  TreeLayout out;
  const std::vector<NodeId> roots = shape.roots();
  if (roots.empty()) return out;

  // Opened nodes: every ancestor of a focus node...
  std::unordered_set<NodeId> opened, walked;
  for (NodeId n : options.open)
    if (index.subtree_nodes(n) > 0) opened.insert(n);
  for (NodeId f : options.focus) {
    if (index.subtree_nodes(f) == 0) continue;  // not in this tree
    // Stops at an ancestor already walked from another focus node: the rest is done.
    for (NodeId p = index.parent(f); p != kNoNode && walked.insert(p).second; p = index.parent(p)) opened.insert(p);
  }
  // ... and the top levels, breadth-first, while the items stay within the budget.
  {
    size_t items = roots.size();
    std::vector<NodeId> level = roots, next;
    bool full = false;
    while (!level.empty() && !full) {
      next.clear();
      for (NodeId n : level) {
        const std::vector<NodeId> kids = shape.children(n);
        if (kids.empty()) continue;
        if (!opened.count(n)) {
          if (items + kids.size() > options.budget) {
            full = true;
            break;
          }
          items += kids.size();
          opened.insert(n);
        }
        next.insert(next.end(), kids.begin(), kids.end());
      }
      level.swap(next);
    }
  }
  const std::unordered_set<NodeId> focus(options.focus.begin(), options.focus.end());

  // Items in pre-order (explicit stack: deep kd-trees), children in the structure's order.
  struct Pending {
    NodeId node;
    int parent;
    int depth;
  };
  std::vector<Pending> stack;
  for (size_t i = roots.size(); i-- > 0;) stack.push_back({roots[i], -1, 0});
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    const TreeNodeInfo info = shape.info(p.node);
    TreeItem item;
    item.node = p.node;
    item.parent = p.parent;
    item.depth = p.depth;
    item.leaf = info.leaf;
    item.prims = info.prims;
    item.subtree_nodes = std::max<uint32_t>(index.subtree_nodes(p.node), 1);
    const bool open = !info.leaf && opened.count(p.node) > 0;
    if (!info.leaf && !open && !focus.count(p.node)) {
      item.kind = TreeItem::Kind::Collapsed;
      out.collapsed_nodes += item.subtree_nodes;
    }
    const int self = static_cast<int>(out.items.size());
    if (p.parent >= 0) out.items[static_cast<size_t>(p.parent)].children.push_back(self);
    out.item_of[p.node] = self;
    out.rows = std::max(out.rows, p.depth + 1);
    out.items.push_back(std::move(item));
    if (open) {
      const std::vector<NodeId> kids = shape.children(p.node);
      for (size_t i = kids.size(); i-- > 0;) stack.push_back({kids[i], self, p.depth + 1});
    }
  }
  // Columns: reverse pre-order visits children before parents. Leaf slots must follow the
  // pre-order, so they are numbered in a forward pass first.
  float slot = 0.0f;
  for (TreeItem& it : out.items)
    if (it.children.empty()) it.x = slot++;
  for (size_t i = out.items.size(); i-- > 0;) {
    TreeItem& it = out.items[i];
    if (it.children.empty()) continue;
    it.x = 0.5f * (out.items[static_cast<size_t>(it.children.front())].x +
                   out.items[static_cast<size_t>(it.children.back())].x);
  }
  out.columns = slot;
  return out;
}

// ---------------------------------------------------------------------------------------
// States

TraceStates::TraceStates(std::span<const accel::TraceEvent> events) : steps_(events.size()) {
  current_.resize(events.size(), kNoNode);
  NodeId current = kNoNode;
  for (size_t s = 0; s < events.size(); ++s) {
    const accel::TraceEvent& e = events[s];
    if (e.kind == accel::TraceEventKind::Visit || e.kind == accel::TraceEventKind::EnterCell) current = e.node;
    current_[s] = current;
    if (names_node(e.kind) && e.node != kNoNode) per_node_[e.node].push_back({s, e.kind, e.reason});
  }
}

NodeId TraceStates::current(size_t step) const {
  if (current_.empty()) return kNoNode;
  return current_[std::min(step, current_.size() - 1)];
}

TreeNodeStatus TraceStates::at(NodeId node, size_t step) const {
  TreeNodeStatus out;
  const auto it = per_node_.find(node);
  if (it == per_node_.end()) return out;
  const std::vector<NodeEvent>& list = it->second;
  const auto last = std::upper_bound(list.begin(), list.end(), step,
                                     [](size_t s, const NodeEvent& e) { return s < e.step; });
  if (last == list.begin()) return out;
  const NodeEvent& e = *(last - 1);
  out.step = e.step;
  using K = accel::TraceEventKind;
  switch (e.kind) {
    case K::Push: out.state = TreeNodeState::OnStack; break;
    case K::Cull:
      out.state = TreeNodeState::Culled;
      out.reason = e.reason;
      break;
    default: out.state = TreeNodeState::Visited; break;  // Visit, EnterCell, Pop
  }
  if (current(step) == node && out.state != TreeNodeState::Culled) out.state = TreeNodeState::Current;
  return out;
}

TreeNodeStatus replay_state(const accel::BuildReplay& replay, NodeId slot, NodeId current_slot) {
  TreeNodeStatus out;
  const auto& nodes = replay.nodes();
  if (slot >= nodes.size() || nodes[slot].gone) return out;
  const accel::ReplayNode& n = nodes[slot];
  if (slot == current_slot) out.state = TreeNodeState::Current;
  else if (n.leaf || !n.children.empty() || n.unrecorded) out.state = TreeNodeState::Visited;
  else out.state = TreeNodeState::OnStack;  // created, waiting for its split
  return out;
}

// ---------------------------------------------------------------------------------------
// The grid's cell walk

std::vector<GridWalkRow> grid_walk_rows(std::span<const accel::TraceEvent> events,
                                        std::span<const accel::RecordedVars> vars, const int res[3]) {
  std::vector<GridWalkRow> rows;
  size_t v = 0;  // vars are in event order: one forward walk pairs them with their events
  const bool decode = res[0] > 0 && res[1] > 0 && res[2] > 0;
  for (size_t s = 0; s < events.size(); ++s) {
    const accel::TraceEvent& e = events[s];
    if (e.kind != accel::TraceEventKind::EnterCell) continue;
    GridWalkRow row;
    row.step = s;
    row.cell = e.node;
    row.t0 = e.t0;
    row.t1 = e.t1;
    while (v < vars.size() && vars[v].event < s) ++v;
    const accel::GridDdaVars* dda = nullptr;
    for (size_t k = v; k < vars.size() && vars[k].event == s && !dda; ++k)
      dda = std::get_if<accel::GridDdaVars>(&vars[k].vars);
    if (dda) {
      for (int a = 0; a < 3; ++a) row.xyz[a] = dda->cell[a];
    } else if (decode && e.node != kNoNode) {
      const uint64_t id = e.node, nx = uint64_t(res[0]), ny = uint64_t(res[1]);
      row.xyz[0] = int(id % nx);
      row.xyz[1] = int((id / nx) % ny);
      row.xyz[2] = int(id / (nx * ny));
    }
    // The 3D-DDA steps one axis per cell: the axis whose coordinate changed.
    if (!rows.empty() && row.xyz[0] >= 0) {
      const GridWalkRow& prev = rows.back();
      for (int a = 0; a < 3; ++a)
        if (row.xyz[a] != prev.xyz[a]) row.stepped_axis = a;
    }
    rows.push_back(row);
  }
  return rows;
}

int grid_current_row(const std::vector<GridWalkRow>& rows, size_t step) {
  const auto it = std::upper_bound(rows.begin(), rows.end(), step,
                                   [](size_t s, const GridWalkRow& r) { return s < r.step; });
  return static_cast<int>(it - rows.begin()) - 1;
}

// ---------------------------------------------------------------------------------------
// SAH cost

SubtreeSummary summarize_subtree(const TreeShape& shape, NodeId node, const SahConstants& k) {
  struct Entry {
    int parent;
    float area;
    double cost;
  };
  SubtreeSummary out;
  std::vector<Entry> order;  // pre-order: every node before its descendants
  struct Pending {
    NodeId node;
    int parent;
    int depth;
  };
  std::vector<Pending> stack{{node, -1, 0}};
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    const TreeNodeInfo info = shape.info(p.node);
    const int self = static_cast<int>(order.size());
    order.push_back({p.parent, info.area, info.leaf ? k.ci * double(info.prims) : k.ct});
    if (info.leaf) {
      ++out.leaves;
      out.prim_refs += info.prims;
      out.max_depth = std::max(out.max_depth, p.depth);
    } else {
      for (NodeId c : shape.children(p.node)) stack.push_back({c, self, p.depth + 1});
    }
  }
  // Reverse pre-order: a node's cost is complete before it is added to its parent's.
  for (size_t i = order.size(); i-- > 1;) {
    const Entry& e = order[i];
    Entry& parent = order[static_cast<size_t>(e.parent)];
    const double ratio = parent.area > 0.0f ? double(e.area) / double(parent.area) : 1.0;
    parent.cost += ratio * e.cost;
  }
  out.nodes = order.size();
  out.sah_cost = order.empty() ? 0.0 : order[0].cost;
  return out;
}

double subtree_sah_cost(const TreeShape& shape, NodeId node, const SahConstants& k) {
  return summarize_subtree(shape, node, k).sah_cost;
}

}  // namespace viz
