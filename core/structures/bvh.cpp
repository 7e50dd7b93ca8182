#include "structures/bvh.h"

namespace accel {

std::vector<ParamSpec> hierarchy_param_specs() {
  std::vector<ParamSpec> specs = bvh_builder_param_specs();
  specs.push_back({"traversal", ParamSpec::Type::Choice, "ordered", 0, 0, {"dfs", "ordered", "pqueue"},
                   "node order: depth-first in tree order, nearer child first with skipping, or a priority "
                   "queue by entry distance (lecture)"});
  return specs;
}

TraversalOrder traversal_order(const ParamSet& params) {
  const std::string& t = params.get_choice("traversal");
  return t == "dfs" ? TraversalOrder::Dfs : t == "pqueue" ? TraversalOrder::PriorityQueue : TraversalOrder::Ordered;
}

void add_hierarchy_option_lines(const BvhBuildOptions& options, TraversalOrder order, BuildStats* s) {
  s->extra.push_back({"builder", builder_name(options.builder)});
  static constexpr const char* kOrder[] = {"dfs", "ordered", "pqueue"};
  s->extra.push_back({"traversal", kOrder[int(order)]});
}

std::vector<ParamSpec> bvh_param_specs() {
  std::vector<ParamSpec> specs = hierarchy_param_specs();
  specs.push_back({"width", ParamSpec::Type::Choice, "4", 0, 0, {"2", "4"},
                   "children per node: 2 is the lecture's binary tree, 4 collapses it into nodes whose four "
                   "boxes are tested at once with SSE (faster)"});
  return specs;
}

std::unique_ptr<Structure> make_bvh(const ParamSet& params) {
  // The layout is a class, not a branch in every query: width is read once, here.
  if (params.get_choice("width") == "2") return std::make_unique<BinaryBvh>();
  return std::make_unique<WideBvh>();
}

BuildStats BinaryBvh::compute_stats() const {
  BuildStats s = Hierarchy::compute_stats();
  s.extra.push_back({"width", "2"});
  return s;
}

}  // namespace accel
