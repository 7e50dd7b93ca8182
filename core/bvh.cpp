#include "bvh.h"

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

}  // namespace accel
