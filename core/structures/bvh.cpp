#include "structures/bvh.h"

namespace accel {

std::vector<ParamSpec> Bvh::param_specs() { return bvh_param_specs(); }

Status Bvh::build_impl(const Scene& scene, const ParamSet& params) {
  width_ = hierarchy_options(params).width;
  // The 4-wide layout tests a leaf's triangles four at a time: the SAH builders know it.
  const BuildTree tree = build_tree(scene, params, width_ == 2 ? 1 : 4);
  wide_.clear();
  if (width_ == 2)
    store_binary(tree);
  else
    wide_.build(scene, tree);
  return {};
}

BuildStats Bvh::compute_stats() const {
  BuildStats s;
  if (width_ == 2) {
    s = Hierarchy::compute_stats();
  } else {
    wide_.add_stats(options_, &s);
    add_option_lines(&s);
  }
  s.extra.push_back({"width", std::to_string(width_)});
  return s;
}

void Bvh::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  if (width_ == 2) return Hierarchy::for_each_node(fn);
  for (NodeId i = 0; i < wide_.size(); ++i) fn(wide_.node_view(i));
}

NodeView Bvh::node_view(NodeId id) const {
  return width_ == 2 ? Hierarchy::node_view(id) : wide_.node_view(id);
}

std::vector<uint32_t> Bvh::node_prims(NodeId id) const {
  return width_ == 2 ? Hierarchy::node_prims(id) : wide_.node_prims(id);
}

}  // namespace accel
