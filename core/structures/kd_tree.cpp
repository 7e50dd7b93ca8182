// kd-tree parameters, build (reading them and running kd_builder.h's builder), statistics
// and node views.
//
// Index
//   [SECTION] Parameters
//   [SECTION] KdTree
#include "structures/kd_tree.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "structures/kd_builder.h"

namespace accel {

//-----------------------------------------------------------------------------
// [SECTION] Parameters
//-----------------------------------------------------------------------------

const ParamTable<KdBuildOptions>& KdTree::param_table() {
  using O = KdBuildOptions;
  static const auto table =
      ParamTable<O>()
          .choice("split", &O::split,
                  std::vector<std::pair<std::string, KdSplit>>{
                      {"middle", KdSplit::Middle}, {"median", KdSplit::Median}, {"sah", KdSplit::Sah}},
                  "split position: middle of the node's region, median of its triangles' centres, or the SAH "
                  "minimum over all three axes (Wald & Havran 2006)")
          .choice("axis", &O::axis,
                  std::vector<std::pair<std::string, KdAxis>>{{"round_robin", KdAxis::RoundRobin},
                                                             {"longest", KdAxis::Longest}},
                  "split axis for middle/median: x,y,z by depth, or the longest axis of the node's region (sah tries "
                  "all three and ignores this)")
          .integer("max_depth", &O::max_depth, 0, kKdMaxDepth,
                   "deepest leaf (root = 0); 0 = auto, round(8 + 1.3 log2 N) as in pbrt")
          .integer("leaf_size", &O::leaf_size, 1, 1024,
                   "a node with at most this many triangles becomes a leaf (sah may stop earlier)")
          .number("ct", &O::ct, 0.01, 1000, "SAH cost of one traversal step")
          .number("ci", &O::ci, 0.01, 1000,
                  "SAH cost of one ray/triangle test (only ci/ct matters: higher = deeper trees, smaller leaves)")
          .number("empty_bonus", &O::empty_bonus, 0, 0.95,
                  "SAH cost factor (1 - empty_bonus) for a split that cuts off empty space")
          .choice("clip", &O::clip, std::vector<std::pair<std::string, bool>>{{"on", true}, {"off", false}},
                  "perfect splits: clip triangles to the node's region before choosing and distributing splits");
  return table;
}

//-----------------------------------------------------------------------------
// [SECTION] KdTree
//-----------------------------------------------------------------------------

Status KdTree::build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) {
  scene_ = nullptr;
  data_ = KdTreeData{};
  KdBuildOptions o = param_table().apply(params);
  o.memory_limit = build_memory_limit(control);
  auto built = build_kd_tree(scene, o, control, recorder);
  if (!built) return built.error();
  data_ = std::move(built.value());
  options_ = o;
  scene_ = &scene;
  return {};
}

namespace {

/// Depth-first walk over all nodes in id (pre-)order with their regions.
template <class Fn>
void walk_nodes(const KdTreeData& data, Fn&& fn) {
  struct Item {
    NodeId id;
    int depth;
    Aabb box;
  };
  std::vector<Item> stack{{0, 0, data.root_box}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    fn(item.id, item.depth, item.box);
    const KdNode& node = data.nodes[item.id];
    if (node.leaf()) continue;
    stack.push_back({node.above_child(), item.depth + 1, kd_child_box(item.box, node.axis(), node.split(), true)});
    stack.push_back({item.id + 1, item.depth + 1, kd_child_box(item.box, node.axis(), node.split(), false)});
  }
}

NodeView make_view(const KdTreeData& data, NodeId id, int depth, const Aabb& box) {
  const KdNode& node = data.nodes[id];
  NodeView v;
  v.id = id;
  v.depth = depth;
  v.box = box;
  v.leaf = node.leaf();
  if (node.leaf()) {
    v.prim_count = node.prim_count();
  } else {
    v.split_axis = node.axis();
    v.split_pos = node.split();
  }
  return v;
}

}  // namespace

void KdTree::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  if (data_.nodes.empty()) return;
  walk_nodes(data_, [&](NodeId id, int depth, const Aabb& box) { fn(make_view(data_, id, depth, box)); });
}

NodeView KdTree::node_view(NodeId id) const {
  if (id >= data_.nodes.size()) return NodeView{};
  // Pre-order ids: the below subtree of node n holds ids (n, above), the above one >= above.
  NodeId cur = 0;
  int depth = 0;
  Aabb box = data_.root_box;
  while (cur != id) {
    const KdNode& node = data_.nodes[cur];
    ACCEL_CHECK(!node.leaf());
    const bool above = id >= node.above_child();
    box = kd_child_box(box, node.axis(), node.split(), above);
    cur = above ? node.above_child() : cur + 1;
    ++depth;
  }
  return make_view(data_, id, depth, box);
}

std::vector<uint32_t> KdTree::node_prims(NodeId id) const {
  if (id >= data_.nodes.size() || !data_.nodes[id].leaf()) return {};
  const KdNode& node = data_.nodes[id];
  return {data_.prim_ids.begin() + node.prim_offset(), data_.prim_ids.begin() + node.prim_offset() + node.prim_count()};
}

BuildStats KdTree::compute_stats() const {
  BuildStats s;
  if (data_.nodes.empty()) return s;
  s.nodes = data_.nodes.size();
  s.prim_references = data_.prim_ids.size();
  s.prims = scene_ ? scene_->valid_prims().size() : 0;
  s.memory_bytes = data_.nodes.size() * sizeof(KdNode) + data_.prim_ids.size() * sizeof(uint32_t);
  s.sah_ct = options_.ct;
  s.sah_ci = options_.ci;
  const double root_area = data_.root_box.area();
  double sah = 0.0;
  size_t inner = 0;
  walk_nodes(data_, [&](NodeId id, int depth, const Aabb& box) {
    const KdNode& node = data_.nodes[id];
    const double rel = root_area > 0.0 ? double(box.area()) / root_area : 0.0;
    s.max_depth = std::max(s.max_depth, depth);
    if (node.leaf()) {
      s.add_leaf(node.prim_count());
      sah += options_.ci * double(node.prim_count()) * rel;
    } else {
      ++inner;
      sah += options_.ct * rel;
    }
  });
  if (root_area > 0.0) s.sah_cost = sah;
  s.extra.push_back({"split", kd_split_name(options_.split)});
  if (options_.split != KdSplit::Sah)
    s.extra.push_back({"axis", options_.axis == KdAxis::Longest ? "longest" : "round_robin"});
  s.extra.push_back({"clip (perfect splits)", options_.clip ? "on" : "off"});
  s.extra.push_back({"max_depth limit", std::to_string(data_.max_depth_limit) +
                                            (options_.max_depth == 0 ? " (auto: round(8 + 1.3 log2 N))" : "")});
  s.extra.push_back({"inner nodes", std::to_string(inner)});
  const KdLeafReasons& r = data_.leaf_reasons;
  s.extra.push_back({"leaves by reason", "few_prims " + std::to_string(r.few_prims) + ", max_depth " +
                                             std::to_string(r.max_depth) + ", no_gain " + std::to_string(r.no_gain) +
                                             ", no_progress " + std::to_string(r.no_progress) + ", bad_refines " +
                                             std::to_string(r.bad_refines) + ", thin " + std::to_string(r.thin)});
  return s;
}

std::vector<NodeId> KdTree::node_children(NodeId id) const {
  if (id >= data_.nodes.size() || data_.nodes[id].leaf()) return {};
  return {id + 1, data_.nodes[id].above_child()};
}

}  // namespace accel
