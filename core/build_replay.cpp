#include "build_replay.h"

#include <algorithm>
#include <cmath>

namespace accel {

void BuildReplay::reset() {
  applied_ = 0;
  nodes_.clear();
  slot_of_.clear();
  grid_ = ReplayGrid{};
  scene_box_ = Aabb{};
  live_nodes_ = leaves_ = references_ = 0;
}

void BuildReplay::seek(size_t k) {
  k = std::min(k, steps());
  if (k < applied_) reset();
  while (applied_ < k) apply(trace_->events[applied_++]);
}

uint32_t BuildReplay::create(uint32_t id) {
  if (id >= slot_of_.size()) slot_of_.resize(size_t(id) + 1 + slot_of_.size() / 2, kNoBuildNode);
  // A builder may reuse an id only for the same node (insertion re-records its leaves); a
  // fresh Node event then restarts it.
  uint32_t s = slot_of_[id];
  if (s == kNoBuildNode || nodes_[s].gone) {
    s = uint32_t(nodes_.size());
    nodes_.emplace_back();
    slot_of_[id] = s;
    ++live_nodes_;
  }
  nodes_[s].id = id;
  return s;
}

void BuildReplay::remove_subtree(uint32_t s) {
  ReplayNode& n = nodes_[s];
  if (n.gone) return;
  n.gone = true;
  --live_nodes_;
  if (n.leaf) {
    --leaves_;
    references_ -= n.prims.size();
  }
  const std::vector<uint32_t> children = n.children;
  for (uint32_t c : children) remove_subtree(c);
}

void BuildReplay::apply(const BuildEvent& e) {
  const uint32_t s = e.node == kNoBuildNode ? kNoBuildNode : slot(e.node);
  switch (e.kind) {
    case BuildEventKind::SceneBox: scene_box_ = e.box; break;
    case BuildEventKind::GridResolution: apply_grid_resolution(e); break;
    case BuildEventKind::GridInsert: apply_grid_insert(e); break;
    case BuildEventKind::Node:
    case BuildEventKind::Unrecorded: apply_node(e); break;
    case BuildEventKind::Axis:
      if (s != kNoBuildNode) nodes_[s].split_axis = e.axis;
      break;
    case BuildEventKind::Candidates: break;  // drawn from the event itself (the cost plot)
    case BuildEventKind::Split:
      if (s != kNoBuildNode) {
        nodes_[s].split_axis = e.axis;
        nodes_[s].split_pos = e.pos;
      }
      break;
    case BuildEventKind::Leaf: apply_leaf(e, s); break;
    case BuildEventKind::Subdivide: break;  // the eight (quadtree: four) children follow as Node events
    case BuildEventKind::Merge: apply_merge(e); break;
    case BuildEventKind::InsertStep:
      if (s != kNoBuildNode) nodes_[s].box = e.box;
      break;
    case BuildEventKind::Collapse: apply_collapse(e, s); break;
    case BuildEventKind::Replace: apply_replace(e, s); break;
    case BuildEventKind::Fit:
      if (s != kNoBuildNode) {
        nodes_[s].box = e.box;
        nodes_[s].sphere = e.sphere;
      }
      break;
    case BuildEventKind::Done: break;
  }
}

void BuildReplay::apply_grid_resolution(const BuildEvent& e) {
  grid_.resolved = true;
  grid_.box = e.box;
  grid_.res[0] = int(e.a);
  grid_.res[1] = int(e.b);
  grid_.res[2] = int(e.count);
  grid_.cells.assign(size_t(e.a) * e.b * e.count, {});
}

void BuildReplay::apply_grid_insert(const BuildEvent& e) {
  for (uint32_t i = 0; i < e.list_count; ++i) {
    const uint32_t cell = trace_->list(e)[i];
    if (cell < grid_.cells.size()) grid_.cells[cell].push_back(e.prim);
  }
  references_ += e.list_count;
}

void BuildReplay::apply_node(const BuildEvent& e) {
  const uint32_t parent = e.parent == kNoBuildNode ? kNoBuildNode : slot(e.parent);
  const uint32_t n = create(e.node);
  ReplayNode& node = nodes_[n];
  node.parent = parent;
  node.depth = e.depth;
  node.box = e.box;
  node.centroids = e.centroids;
  node.prim_count = e.count;
  node.unrecorded = e.kind == BuildEventKind::Unrecorded;
  if (e.kind == BuildEventKind::Node) node.prims.assign(trace_->list(e), trace_->list(e) + e.list_count);
  if (parent != kNoBuildNode) nodes_[parent].children.push_back(n);
}

void BuildReplay::apply_leaf(const BuildEvent& e, uint32_t s) {
  if (s == kNoBuildNode || nodes_[s].gone) return;
  ReplayNode& node = nodes_[s];
  // A leaf made of a subtree (bottom-up and insertion trees are collapsed into leaves
  // afterwards) replaces its children; a second Leaf event on a leaf replaces the first.
  const std::vector<uint32_t> children = node.children;
  for (uint32_t c : children) remove_subtree(c);
  node.children.clear();
  if (node.leaf)
    references_ -= node.prims.size();
  else
    ++leaves_;
  node.leaf = true;
  node.prims.assign(trace_->list(e), trace_->list(e) + e.list_count);
  node.prim_count = e.list_count;
  references_ += e.list_count;
}

void BuildReplay::apply_merge(const BuildEvent& e) {
  const uint32_t a = slot(e.a), b = slot(e.b);
  const uint32_t n = create(e.node);
  ReplayNode& node = nodes_[n];
  node.box = e.box;
  node.leaf = false;
  // The new node takes a's place under a's parent (insertion puts it between them).
  const uint32_t up = a != kNoBuildNode ? nodes_[a].parent : kNoBuildNode;
  node.parent = up;
  if (up != kNoBuildNode) std::replace(nodes_[up].children.begin(), nodes_[up].children.end(), a, n);
  node.children.clear();
  for (uint32_t c : {a, b}) {
    if (c == kNoBuildNode) continue;
    nodes_[c].parent = n;
    nodes_[n].children.push_back(c);
  }
}

void BuildReplay::apply_collapse(const BuildEvent& e, uint32_t s) {
  const uint32_t c = slot(e.a);
  if (s == kNoBuildNode || c == kNoBuildNode) return;
  std::vector<uint32_t>& kids = nodes_[s].children;
  const auto at = std::find(kids.begin(), kids.end(), c);
  if (at == kids.end()) return;
  const std::vector<uint32_t> grand = nodes_[c].children;
  const auto pos = kids.erase(at);
  kids.insert(pos, grand.begin(), grand.end());
  for (uint32_t g : grand) nodes_[g].parent = s;
  nodes_[c].children.clear();
  nodes_[c].gone = true;
  --live_nodes_;
}

void BuildReplay::apply_replace(const BuildEvent& e, uint32_t s) {
  const uint32_t old = slot(e.a);
  if (s == kNoBuildNode || old == kNoBuildNode || nodes_[old].gone) return;
  const uint32_t up = nodes_[old].parent;
  if (up != kNoBuildNode) std::replace(nodes_[up].children.begin(), nodes_[up].children.end(), old, s);
  nodes_[s].parent = up;
  nodes_[old].parent = kNoBuildNode;
  remove_subtree(old);
}

double BuildReplay::sah_cost(double ct, double ci, int prims_per_test) const {
  const auto area = [](const ReplayNode& n) {
    return n.sphere.radius >= 0.0f ? 4.0 * 3.14159265358979323846 * double(n.sphere.radius) * double(n.sphere.radius)
                                   : double(n.box.area());
  };
  double root_area = 0.0;
  for (const ReplayNode& n : nodes_)
    if (!n.gone && n.parent == kNoBuildNode) root_area = std::max(root_area, area(n));
  if (nodes_.empty() || root_area <= 0.0) return std::nan("");
  double cost = 0.0;
  for (const ReplayNode& n : nodes_) {
    if (n.gone) continue;
    const bool open = n.children.empty();  // a leaf, or a node not split yet: priced as a leaf
    const double tests = double((size_t(n.prim_count) + size_t(prims_per_test) - 1) / size_t(prims_per_test));
    cost += (open ? ci * tests : ct) * area(n) / root_area;
  }
  return cost;
}

std::vector<int> BuildReplay::depths() const {
  std::vector<int> depth(nodes_.size(), -1);
  for (size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].gone) continue;
    int d = 0;
    for (uint32_t p = nodes_[i].parent; p != kNoBuildNode; p = nodes_[p].parent) ++d;
    depth[i] = d;
  }
  return depth;
}

}  // namespace accel
